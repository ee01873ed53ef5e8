#include "cli.hpp"

namespace omninav::cli {

void add_render_command(CLI::App& app, const GlobalOptions& /*global*/) {
  app.add_subcommand("render", "(not yet available)");
}

}  // namespace omninav::cli
