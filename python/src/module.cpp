// The Python module omninav._omninav: the library's high-level entry points, with images as
// numpy arrays (python/omninav/__init__.py re-exports them; the .pyi stubs describe them).
#include "bind.hpp"

PYBIND11_MODULE(_omninav, m) {
  m.doc() =
      "omninav: appearance-based topological mapping and navigation with omnidirectional "
      "cameras. Images are numpy arrays (H x W x 3 uint8 BGR, or H x W grey), angles are in "
      "radians (names end in _rad), errors are omninav.Error subclasses. Long calls release "
      "the GIL; an object (a Compass, a Map, a Localiser) is for one thread at a time.";
  m.attr("__version__") = OMNINAV_VERSION;
  using namespace omninav::python;
  bind_errors(m);
  bind_core(m);
  bind_config(m);
  bind_io(m);
  bind_compass(m);
  bind_signature(m);
  bind_memory(m);
  bind_sim(m);
}
