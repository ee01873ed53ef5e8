#include "cli.hpp"

#include <iostream>

#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"

namespace omninav::cli {

int run(int argc, const char* const* argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  return run(args);
}

int run(const std::vector<std::string>& args) {
  CLI::App app{
      "omninav: appearance-based topological mapping and navigation with omnidirectional "
      "cameras.\nBuild a visual memory of a room from panoramic images, localise a query image "
      "in it,\nand drive to a goal image. Run 'omninav <command> --help' for a command's "
      "options.",
      "omninav"};
  app.set_version_flag("--version", std::string("omninav ") + OMNINAV_VERSION);
  app.require_subcommand(1);
  app.fallthrough();

  GlobalOptions global;
  global.config_dir = OMNINAV_DEFAULT_CONFIG_DIR;
  app.add_option("--config-dir", global.config_dir,
                 "Folder of YAML configuration files (camera.yaml, worlds.yaml, ...)")
      ->capture_default_str()
      ->check(CLI::ExistingDirectory);
  app.add_flag("-q,--quiet", global.quiet, "Print errors only");
  app.add_flag("-v,--verbose", global.verbose, "Print debugging detail");
  app.parse_complete_callback([&] {
    set_log_level(global.quiet     ? LogLevel::kError
                  : global.verbose ? LogLevel::kDebug
                                   : LogLevel::kInfo);
  });

  add_render_command(app, global);
  add_unwrap_command(app, global);
  add_compass_command(app, global);
  add_explore_command(app, global);
  add_localise_command(app, global);
  add_export_command(app, global);
  add_organise_command(app, global);
  add_route_command(app, global);
  add_navigate_command(app, global);
  add_demo_command(app, global);
  add_evaluate_command(app, global);

  try {
    std::vector<std::string> reversed(args.rbegin(),
                                      args.rend());  // CLI11 parses a reversed vector
    app.parse(reversed);
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForAllHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForVersion& version) {
    return app.exit(version);
  } catch (const CLI::ParseError& error) {
    app.exit(error);  // prints the message and a hint to use --help
    return 2;         // a usage error, whatever CLI11's own code for it
  } catch (const UsageError& error) {
    log_error(error.what());
    return 2;
  } catch (const Error& error) {
    log_error(error.what());
    return 1;
  } catch (const std::exception& error) {
    // Not one of ours: still one line and a non-zero exit, never an abort.
    log_error(std::string("unexpected failure: ") + error.what());
    return 1;
  }
  return 0;
}

}  // namespace omninav::cli
