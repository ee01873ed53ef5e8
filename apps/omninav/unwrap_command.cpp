#include "cli.hpp"

namespace omninav::cli {

void add_unwrap_command(CLI::App& app, const GlobalOptions& /*global*/) {
  app.add_subcommand("unwrap", "(not yet available)");
}

}  // namespace omninav::cli
