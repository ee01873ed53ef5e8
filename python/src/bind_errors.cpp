// The library's typed exceptions (core/errors.hpp) as Python classes with the same one-line
// messages: omninav.Error (a RuntimeError) and its subclasses ConfigError, InputError and
// UsageError.
#include "bind.hpp"
#include "omninav/core/errors.hpp"

namespace omninav::python {

void bind_errors(py::module_& m) {
  // pybind11 tries translators newest first, so the subclasses are registered after their base.
  auto& error = py::register_exception<Error>(m, "Error", PyExc_RuntimeError);
  error.attr("__doc__") = "Base of every error omninav reports; str() is the one-line message.";
  py::register_exception<ConfigError>(m, "ConfigError", error).attr("__doc__") =
      "A configuration file or value is wrong (unknown key, bad type, out of range).";
  py::register_exception<InputError>(m, "InputError", error).attr("__doc__") =
      "An input file, sequence or array is wrong (unreadable, corrupt, inconsistent); the "
      "message names it.";
  py::register_exception<UsageError>(m, "UsageError", error).attr("__doc__") =
      "The arguments ask for something that cannot be done.";
  // Named as the package exports them: omninav.InputError, not omninav._omninav.InputError.
  for (const char* name : {"Error", "ConfigError", "InputError", "UsageError"}) {
    m.attr(name).attr("__module__") = "omninav";
  }
}

}  // namespace omninav::python
