#include "cli.hpp"

#include <iostream>
#include <limits>
#include <sstream>

#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/core/parse.hpp"

namespace omninav::cli {

CLI::Validator NumberRange(double min, double max) {
  const std::string range = max == std::numeric_limits<double>::max()
                                ? ">= " + general(min)
                                : "in [" + general(min) + ", " + general(max) + "]";
  return CLI::Validator(
      [min, max, range](std::string& text) -> std::string {
        double value = 0.0;
        try {
          value = parse_double(text, "value");  // finite, or InputError
        } catch (const InputError&) {
          return "'" + text + "' is not a finite number " + range;
        }
        if (value < min || value > max) return "'" + text + "' is not " + range;
        return "";
      },
      range);
}

void add_format_option(CLI::App* command, OutputFormat& format) {
  command
      ->add_option_function<std::string>(
          "--format",
          [&format](const std::string& text) {
            format = text == "csv"    ? OutputFormat::kCsv
                     : text == "json" ? OutputFormat::kJson
                                      : OutputFormat::kText;
          },
          "text, csv or json")
      ->check(CLI::IsMember({"text", "csv", "json"}))
      ->default_str("text");
}

// The output folder must not be a file, nor the folder the input images live in (the PNGs
// could overwrite them), nor hold anything unless --force.
void check_output_folder(const std::filesystem::path& out, bool force,
                         const std::filesystem::path& input) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (!fs::exists(out, error)) return;
  if (!fs::is_directory(out, error)) {
    throw UsageError(out.string() + ": exists and is not a folder");
  }
  const fs::path input_folder = fs::is_directory(input, error) ? input : input.parent_path();
  if (!input.empty() && same_file(out, input_folder.empty() ? fs::path(".") : input_folder)) {
    throw UsageError(out.string() + ": is the input's folder; write the panoramas elsewhere");
  }
  if (!force && !fs::is_empty(out, error)) {
    throw UsageError(out.string() + ": is not empty; choose an empty folder or add --force");
  }
}

void add_old_flag_name(CLI::App* command, const std::string& old_name, const std::string& name,
                       bool& value) {
  command
      ->add_flag_function(old_name,
                          [&value, old_name, name](std::int64_t) {
                            log_warning(old_name + " is now " + name + "; the old name will go");
                            value = true;
                          })
      ->group("");
}

void add_old_option_name(CLI::App* command, const std::string& old_name, const std::string& name,
                         std::filesystem::path& value) {
  command
      ->add_option_function<std::string>(
          old_name,
          [&value, old_name, name](const std::string& given) {
            log_warning(old_name + " is now " + name + "; the old name will go");
            value = given;
          })
      ->group("");
}

// The configuration folder beside the program: <prefix>/share/omninav/config for a program in
// <prefix>/bin, as installed and as in the build tree (CMake links build/share/omninav/config
// to the sources' config/). Found from /proc/self/exe at run time, so that the program holds no
// path of the machine it was built on.
std::filesystem::path default_config_dir() {
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return "config";
  return program.parent_path().parent_path() / "share" / "omninav" / "config";
}

std::ostream& summary(const GlobalOptions& global) {
  static std::ostream nowhere(nullptr);  // a stream without a buffer writes nothing
  return global.quiet ? nowhere : std::cout;
}

int run(int argc, const char* const* argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  return run(args);
}

namespace {

// Thrown once a line is parsed and checked, when only that was asked (check_command_line).
struct ParsedOnly {};

int parse_and_run(const std::vector<std::string>& args, bool parse_only) {
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
  global.config_dir = default_config_dir();
  app.add_option("--config-dir", global.config_dir,
                 "Folder of YAML configuration files (camera.yaml, worlds.yaml, ...; default: "
                 "share/omninav/config beside the program's bin/)")
      ->capture_default_str()
      ->check(CLI::ExistingDirectory);
  app.add_flag("-q,--quiet", global.quiet, "Print errors only");
  app.add_flag("-v,--verbose", global.verbose, "Print debugging detail");
  // Runs after every option and requirement is checked, before the command's own callback.
  app.parse_complete_callback([&] {
    if (parse_only) throw ParsedOnly{};
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
  add_completion_command(app);

  try {
    // An unknown command is named as such (CLI11 would say "A subcommand is required").
    for (std::size_t i = 0; i < args.size(); ++i) {
      if (args[i] == "--config-dir") {
        ++i;  // its value
      } else if (!args[i].empty() && args[i][0] != '-') {
        std::string commands;
        bool known = false;
        for (const CLI::App* command : app.get_subcommands({})) {
          commands += (commands.empty() ? "" : ", ") + command->get_name();
          known = known || command->get_name() == args[i];
        }
        if (!known) {
          throw UsageError("unknown command '" + args[i] + "' (commands: " + commands + ")");
        }
        break;
      }
    }
    std::vector<std::string> reversed(args.rbegin(),
                                      args.rend());  // CLI11 parses a reversed vector
    app.parse(reversed);
    flush_standard_output();  // a full disk or a closed pipe is a failure, not a success
  } catch (const ParsedOnly&) {
    return 0;
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

}  // namespace

int run(const std::vector<std::string>& args) {
  return parse_and_run(args, false);
}

int check_command_line(const std::vector<std::string>& args) {
  return parse_and_run(args, true);
}

}  // namespace omninav::cli
