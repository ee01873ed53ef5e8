#include "cli.hpp"

namespace omninav::cli {

void add_demo_command(CLI::App& app, const GlobalOptions& /*global*/) {
  app.add_subcommand("demo", "(not yet available)");
}

}  // namespace omninav::cli
