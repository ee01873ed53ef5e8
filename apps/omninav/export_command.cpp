#include "cli.hpp"

namespace omninav::cli {

void add_export_command(CLI::App& app, const GlobalOptions& /*global*/) {
  app.add_subcommand("export", "(not yet available)");
}

}  // namespace omninav::cli
