#include "cli.hpp"

namespace omninav::cli {

void add_compass_command(CLI::App& app, const GlobalOptions& /*global*/) {
  app.add_subcommand("compass", "(not yet available)");
}

}  // namespace omninav::cli
