// omninav export: a map's places and edges for other tools (CSV, GraphML), and the figures of
// Menegatti et al. 2004, §2, from a map of a rendered grid.
#include <iostream>
#include <optional>

#include "cli.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/memory/export.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/report/memory_figures.hpp"

namespace omninav::cli {
namespace {

struct ExportOptions {
  std::filesystem::path map;
  std::string what = "places";
  std::string format = "csv";
  std::filesystem::path out;
};

void run_export(const GlobalOptions& global, const ExportOptions& options) {
  if (!options.out.empty() && options.what != "figures")
    check_output_path(options.out, {options.map});
  const memory::VisualMemory map = memory::load_map(options.map);
  if (options.what == "figures") {
    if (options.out.empty()) throw UsageError("--what figures needs --out <folder>");
    const report::SignatureFigures figures = report::write_signature_figures(map, options.out);
    summary(global) << figures.summary;
    log_info("wrote " + std::to_string(figures.files.size()) + " files to " + options.out.string());
    return;
  }
  std::optional<OutputFile> file;
  if (!options.out.empty()) file.emplace(options.out);
  std::ostream& out = file ? file->stream() : std::cout;
  if (options.format == "graphml") {
    // GraphML holds the whole graph: places as nodes, edges as edges.
    memory::write_graphml(map, out);
  } else if (options.what == "edges") {
    memory::write_edges_csv(map, out);
  } else {
    memory::write_places_csv(map, out);
  }
  if (file) file->commit();
}

}  // namespace

void add_export_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* command = app.add_subcommand(
      "export",
      "Export a map: its places or edges as CSV (degrees, units in the column names), the "
      "whole graph as GraphML, or, for a map of a rendered grid, the figures of "
      "Menegatti et al. 2004, §2 (Figs. 5-7, PNG and CSV; docs/memory.md).");
  command->add_option("map", options->map, "The map, e.g. maps/room.vmem")->required();
  command->add_option("--what", options->what, "places, edges or figures")
      ->check(CLI::IsMember({"places", "edges", "figures"}))
      ->capture_default_str();
  command
      ->add_option("--format", options->format,
                   "csv or graphml (GraphML holds places and edges together)")
      ->check(CLI::IsMember({"csv", "graphml"}))
      ->capture_default_str();
  command->add_option("--out", options->out,
                      "File to write (default: standard output); a folder for --what figures");
  command->callback([&global, options] { run_export(global, *options); });
}

}  // namespace omninav::cli
