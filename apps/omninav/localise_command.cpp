#include "cli.hpp"

namespace omninav::cli {

void add_localise_command(CLI::App& app, const GlobalOptions& /*global*/) {
  app.add_subcommand("localise", "(not yet available)");
}

}  // namespace omninav::cli
