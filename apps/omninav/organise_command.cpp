// omninav organise: the spring-model lattice of a visual memory (Ceres), stored in the map.
#include <cmath>
#include <iostream>

#include "app_config.hpp"
#include "cli.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/format.hpp"
#include "omninav/core/log.hpp"
#include "omninav/core/output_file.hpp"
#include "omninav/evaluation/organised_map.hpp"
#include "omninav/measures/png.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/report/lattice_figures.hpp"

namespace omninav::cli {
namespace {

struct OrganiseOptions {
  std::filesystem::path map;
  double step_m = 0.0;
  bool no_motion = false;
  std::filesystem::path plot;  // --plot: the lattice's picture
};

void run_organise(const GlobalOptions& global, const OrganiseOptions& options) {
  lattice::OrganiseParams params = load_lattice_config(global.config_dir);
  if (options.step_m > 0.0) params.step_m = options.step_m;
  if (options.no_motion) params.motion_constraints = false;
  const std::filesystem::path picture =
      options.plot.empty() ? std::filesystem::path(options.map).replace_extension(".lattice.png")
                           : options.plot;
  check_output_path(picture, {options.map});  // before the work, not after it
  memory::MapStore store(options.map);
  const evaluation::OrganisedMap result = evaluation::organise_stored_map(store, params);
  const memory::VisualMemory& memory = result.memory;
  const lattice::OrganiseResult& organised = result.organised;

  const lattice::DistanceCalibration& calibration = organised.calibration;
  summary(global) << "organised " << memory.place_count() << " places of " << options.map.string()
                  << "\n"
                  << "  scale:    " << fixed(calibration.step_m, 3)
                  << " m between consecutive places ("
                  << lattice::to_string(calibration.step_source) << ")";
  if (organised.travelled_links > 0) {
    summary(global) << "\n  pose graph: " << organised.travelled_links
                    << " travelled links (odometry), " << organised.revisits
                    << " revisits confirmed by sequence matching, "
                    << organised.revisits_switched_off
                    << " of them switched off as contradicting the rest\n";
  } else {
    summary(global) << ", dissimilarity " << fixed(calibration.step_dissimilarity, 3)
                    << " per step (median of the places' own), plateau "
                    << fixed(calibration.plateau_dissimilarity, 3) << "\n"
                    << "  springs:  " << organised.lattice.springs_kept << " kept of "
                    << organised.lattice.springs_given << " offered, of "
                    << organised.lattice.place_pairs
                    << " pairs of places (x1 = " << fixed(calibration.correlation_range_m, 3)
                    << " m; weaker than K = " << fixed(params.lattice.min_stiffness, 3)
                    << " dropped), " << organised.lattice.motion_constraints
                    << " motions (directions from the phases"
                    << (params.steps_along_heading ? "; a stream's steps along the headings" : "")
                    << ")\n";
  }
  summary(global) << "  solver:   " << organised.lattice.summary << "\n";
  // The quality needs no ground truth: the lattice against the motions it was solved from.
  const memory::LatticeQuality& quality = organised.quality;
  summary(global) << "  quality:  " << quality.motions << " motions, median residual "
                  << fixed(quality.motion_residual_steps, 2) << " steps, "
                  << fixed(100.0 * quality.motions_off, 1)
                  << " % pointing > 45 deg off the lattice, " << quality.pieces
                  << (quality.pieces == 1 ? " piece" : " pieces") << " before look-alike joins: "
                  << (quality.trustworthy ? "trustworthy" : "NOT TRUSTWORTHY") << "\n";
  if (!quality.trustworthy) {
    log_warning("the lattice of " + options.map.string() + " is not trustworthy: " +
                (quality.pieces > 1
                     ? std::to_string(quality.pieces) +
                           " pieces are placed against each other by look-alikes only"
                     : fixed(100.0 * quality.motions_off, 1) +
                           " % of the motions disagree with it (more than " +
                           fixed(100.0 * params.max_motions_off, 1) + " %)") +
                "; positions on it may be metres off");
  }
  const std::optional<evaluation::LatticeScore>& evaluation = result.score;
  if (evaluation) {
    // An RMSE over no places (a map without interior places) is NaN: said in words.
    const auto rmse = [](double value, const char* places) {
      return std::isnan(value) ? "no " + std::string(places) + " places"
                               : fixed(value, 3) + " " + places;
    };
    summary(global) << "  vs truth: RMSE after Procrustes " << fixed(evaluation->rmse.all, 3)
                    << " spacings (" << rmse(evaluation->rmse.interior, "interior") << ", "
                    << rmse(evaluation->rmse.boundary, "boundary") << "; spacing "
                    << fixed(evaluation->spacing_m, 3) << " m)\n"
                    << "  folds:    " << evaluation->folded.size() << " of "
                    << evaluation->neighbour_triangles
                    << " triangles of true neighbours turned over in the lattice\n";
  }
  measures::save_png(
      report::lattice_picture(memory, organised, evaluation ? &*evaluation : nullptr), picture);
  // The map last: a failure above leaves it as it was.
  store.save(result.memory);
  summary(global) << "  picture:  " << picture.string() << "\n";
}

}  // namespace

void add_organise_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<OrganiseOptions>();
  CLI::App* command = app.add_subcommand(
      "organise",
      "Arrange the places of a visual memory into a 2-D lattice with the spring model "
      "(Menegatti et al. 2004, §3; Ceres): distances from similarity, stiff short springs, "
      "directions of motion from the phases. Stores the positions in the map, prints the "
      "calibration, the solver's report and the lattice's quality (the motions against it; a "
      "warning when it is not trustworthy), and draws <map>.lattice.png. When the map has ground "
      "truth: the truth beside it, the Procrustes RMSE, and the folds (triangles of true "
      "neighbours turned over in the lattice).");
  command->add_option("map", options->map, "The map (.vmem)")->required();
  command
      ->add_option("--step-m", options->step_m,
                   "Metres between consecutive places of the exploration (default: lattice.yaml, "
                   "else the spacing the map was explored with, explore --every-m, else the "
                   "grid spacing its BoB grid database states, grid.separationMM)")
      ->check(NumberRange(0.0, 100.0));
  command->add_flag("--no-motion", options->no_motion,
                    "Springs only: no motions measured from the phases");
  command->add_option("--plot", options->plot,
                      "Where to draw the lattice (default: <map>.lattice.png)");
  add_old_option_name(command, "--picture", "--plot", options->plot);
  command->callback([&global, options] { run_organise(global, *options); });
}

}  // namespace omninav::cli
