#include "cli.hpp"

namespace omninav::cli {

void add_explore_command(CLI::App& app, const GlobalOptions& /*global*/) {
  app.add_subcommand("explore", "(not yet available)");
}

}  // namespace omninav::cli
