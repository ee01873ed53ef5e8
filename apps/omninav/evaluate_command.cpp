// omninav evaluate: every capability measured on every world of a suite (libs/evaluation).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>

#include "cli.hpp"
#include "omninav/config/config_folder.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/evaluation/evaluate.hpp"
#include "omninav/measures/png.hpp"

namespace omninav::cli {
namespace {

struct EvaluateOptions {
  std::string suite = "quick";
  std::filesystem::path out;        // empty: evaluation/<suite name>
  std::vector<std::string> worlds;  // empty: all of the suite's
};

void run_evaluate(const GlobalOptions& global, const EvaluateOptions& options) {
  evaluation::Suite suite = evaluation::load_suite(options.suite, global.config_dir);
  if (!options.worlds.empty()) {
    std::vector<evaluation::SuiteWorld> chosen;
    for (const std::string& label : options.worlds) {
      const auto found =
          std::find_if(suite.worlds.begin(), suite.worlds.end(),
                       [&](const evaluation::SuiteWorld& w) { return w.label == label; });
      if (found == suite.worlds.end()) {
        std::string known;
        for (const evaluation::SuiteWorld& w : suite.worlds)
          known += (known.empty() ? "" : ", ") + w.label;
        throw UsageError("--worlds: the suite has no world " + label + " (it has " + known + ")");
      }
      chosen.push_back(*found);
    }
    suite.worlds = chosen;
  }
  const evaluation::ConfigFolder configuration = config::load_config_folder(global.config_dir);
  const std::filesystem::path out =
      options.out.empty() ? std::filesystem::path("evaluation") / suite.name : options.out;
  std::filesystem::create_directories(out);
  log_info("evaluate: suite " + suite.name + " (" + suite.file.string() + "), " +
           std::to_string(suite.worlds.size()) + " worlds, outputs in " + out.string());
  const std::vector<evaluation::Measure>& columns = evaluation::measures();
  const std::filesystem::path csv = out / "evaluation.csv";
  const std::filesystem::path worst = out / "evaluation_worst.csv";
  const auto start = std::chrono::steady_clock::now();
  std::vector<evaluation::Row> done;
  const evaluation::SuiteEvaluation result = evaluation::evaluate_suite(
      suite, configuration, out, [&](const evaluation::Row& row, std::size_t index) {
        // The table so far, so that an interrupted run leaves its finished worlds.
        done.push_back(row);
        write_output_file(csv, evaluation::table_csv(done, columns));
        write_output_file(worst, evaluation::worst_csv(done, columns));
        const double minutes =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / 60;
        log_info(fmt::format("evaluate: {} done ({} of {}, {:.1f} min)", row.world, index + 1,
                             suite.worlds.size(), minutes));
      });
  const std::filesystem::path picture = out / "evaluation.png";
  const std::filesystem::path commands = out / "commands.sh";
  write_output_file(csv, evaluation::table_csv(result.rows, columns));
  write_output_file(worst, evaluation::worst_csv(result.rows, columns));
  measures::save_png(report::score_table_picture(evaluation::score_table(
                         result.rows, columns, "omninav evaluate --suite " + suite.name)),
                     picture);
  std::string script = "#!/bin/sh\n# The commands that remake every figure of " + csv.string() +
                       " (omninav evaluate --suite " + options.suite + ")\nset -e\n";
  for (const std::string& line : result.commands) script += line + "\n";
  write_output_file(commands, script);

  std::cout << "omninav evaluate --suite " << options.suite << ": " << result.rows.size()
            << " worlds\n\n"
            << evaluation::table_text(result.rows, columns);
  for (const evaluation::Row& row : result.rows) {
    for (const std::string& note : row.notes)
      std::cout << "note: " << row.world << ": " << note << "\n";
  }
  std::cout << "table: " << csv.string() << ", worst rows: " << worst.string()
            << ", picture: " << picture.string()
            << "; the commands that remake each figure: " << commands.string() << "\n";
  if (!result.failed_worlds.empty()) {
    // The table is written, but a world that could not be measured is a failed run.
    std::string failed;
    for (const std::string& world : result.failed_worlds)
      failed += (failed.empty() ? "" : "; ") + world;
    throw InputError(suite.file.string() + ": " + std::to_string(result.failed_worlds.size()) +
                     " of " + std::to_string(result.rows.size()) +
                     " worlds could not be evaluated: " + failed);
  }
}

}  // namespace

void add_evaluate_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<EvaluateOptions>();
  CLI::App* command = app.add_subcommand(
      "evaluate",
      "Measure every capability on every world of a suite (docs/evaluation.md): for each world, "
      "render the routes and run what the commands run (compass --truth on a rotation, a "
      "circle, a wander, a bumpy wander and a saccadic route; explore, organise and localise on "
      "a grid; organise on zig-zag streams; navigate --trials), then print one table (a row per "
      "world, a column per measure, a last row WORST naming the worst family of each column) "
      "and write "
      "evaluation.csv (a row per world), evaluation_worst.csv (the worst row of each column), "
      "evaluation.png and commands.sh (the command lines that remake each "
      "figure) into --out. The same suite gives the same table.");
  command
      ->add_option(
          "--suite", options->suite,
          "quick (CI, a few minutes), full (the benchmark, 45 minutes on two cores) or a YAML file "
          "(config/suites/*.yaml document the keys)")
      ->capture_default_str();
  command->add_option("--out", options->out,
                      "Folder for the table, pictures, databases and maps (default: "
                      "evaluation/<suite name>)");
  command
      ->add_option("--worlds", options->worlds,
                   "Only these rows of the suite (their labels, comma-separated), e.g. to resume "
                   "an interrupted run into another --out")
      ->delimiter(',');
  command->callback([&global, options] { run_evaluate(global, *options); });
}

}  // namespace omninav::cli
