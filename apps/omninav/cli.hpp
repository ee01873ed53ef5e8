#pragma once
// The omninav command line: one file per subcommand (<name>_command.cpp), each thin: parse,
// load config, call the libraries, print. Errors thrown below surface here as one line.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace omninav::cli {

// Options every subcommand shares.
struct GlobalOptions {
  std::filesystem::path config_dir;  // where camera.yaml, worlds.yaml, ... are read from
  bool quiet = false;
  bool verbose = false;
};

// The configuration folder beside the program: <prefix>/share/omninav/config for a program in
// <prefix>/bin (omninav, omninav_ros), as installed and as in the build tree.
std::filesystem::path default_config_dir();

// The range check of every number on the command line: CLI::Range lets NaN through (a NaN
// compares false with both bounds), this refuses anything but a finite number in [min, max].
CLI::Validator NumberRange(double min, double max);

// How a command prints its results (--format): text for people, CSV or JSON for programs.
enum class OutputFormat { kText, kCsv, kJson };

// The --format option of `command`, "text, csv or json", default text.
void add_format_option(CLI::App* command, OutputFormat& format);

// The old spelling of a renamed flag or option (one name per idea across the commands: --force,
// --plot, --out): hidden from --help, still accepted, with a warning that names the new one.
void add_old_flag_name(CLI::App* command, const std::string& old_name, const std::string& name,
                       bool& value);
void add_old_option_name(CLI::App* command, const std::string& old_name, const std::string& name,
                         std::filesystem::path& value);

// The output folder of a command that writes many files (render, unwrap), checked before the
// work: not a file, not the folder the input images live in (when `input` is given), and
// empty unless --force. UsageError otherwise.
void check_output_folder(const std::filesystem::path& out, bool force,
                         const std::filesystem::path& input = {});

// Where a command's summary lines go ("explored ...", "organised ..."): standard output, or
// nowhere with -q. Output the user asked for (--out -, --format csv) goes to std::cout.
std::ostream& summary(const GlobalOptions& global);

// Runs the command line; returns the process exit status: 0 success, 1 an error in the input
// or the configuration, 2 a usage error (bad or missing arguments).
int run(int argc, const char* const* argv);
int run(const std::vector<std::string>& args);  // args without the program name

// Parses `args` as run() does (commands, options, their values and checks), without running
// the command: 0 when omninav would accept the line, else 2 with the usage error printed. The
// tests check every command line of README.md and docs/ with it.
int check_command_line(const std::vector<std::string>& args);

// Each subcommand registers itself; its callback runs when the user picks it.
void add_render_command(CLI::App& app, const GlobalOptions& global);
void add_unwrap_command(CLI::App& app, const GlobalOptions& global);
void add_compass_command(CLI::App& app, const GlobalOptions& global);
void add_explore_command(CLI::App& app, const GlobalOptions& global);
void add_localise_command(CLI::App& app, const GlobalOptions& global);
void add_export_command(CLI::App& app, const GlobalOptions& global);
void add_organise_command(CLI::App& app, const GlobalOptions& global);
void add_route_command(CLI::App& app, const GlobalOptions& global);
void add_navigate_command(CLI::App& app, const GlobalOptions& global);
void add_demo_command(CLI::App& app, const GlobalOptions& global);
void add_evaluate_command(CLI::App& app, const GlobalOptions& global);
void add_completion_command(CLI::App& app);

}  // namespace omninav::cli
