#pragma once
// Organising a visual memory into a lattice (001_5bb151a4e28490b4.txt §3): distances estimated
// from similarity (calibrated without ground truth), springs between places, motion directions
// from the phases, solved by spring_lattice.hpp, and the positions written into the places.

#include <optional>
#include <string>

#include "omninav/lattice/spring_lattice.hpp"
#include "omninav/memory/visual_memory.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::lattice {

struct OrganiseParams {
  // The scale: the distance between consecutive places of the exploration, metres. 0: take it
  // from the map (the exploration's spacing policy, note "exploration.every_m"); a value given
  // here (by the user) wins over the map's.
  double step_m = 0.0;
  int neighbours = 24;                 // springs per place: its most similar places
  double range_fraction = 0.8;         // x₁ where dissimilarity reaches this share of its plateau
  bool motion_constraints = true;      // use the phase-derived directions of motion (§3.4)
  double min_motion_confidence = 0.3;  // skip motion directions measured with less confidence
  LatticeParams lattice;               // correlation_range_m is set by the calibration
};

// Reads the `organise:` section of lattice.yaml.
void load_organise_params(const ConfigReader& section, OrganiseParams& params);

// How dissimilarity maps to distance. Fig. 7: linear at short range, then saturating; we model
// it as D(x) = D_sat·(1 − exp(−x/λ)), whose slope at 0 is the short-range relation
// D_sat/λ, so that x(D) = −λ·ln(1 − D/D_sat) (our reading: the paper only shows the curve).
struct DistanceCalibration {
  double step_m = 0.0;                 // the scale used
  std::string step_source;             // "user" or "map: exploration.every_m"
  double step_dissimilarity = 0.0;     // median dissimilarity between consecutive places
  double plateau_dissimilarity = 0.0;  // D_sat: the 90th percentile of all pairs' dissimilarity
  double length_scale_m = 0.0;         // λ
  double correlation_range_m = 0.0;    // x₁

  double distance_m(double dissimilarity) const;
};

struct OrganiseResult {
  DistanceCalibration calibration;
  std::vector<SpringMeasurement> springs;  // every spring offered to the solver
  std::vector<MotionMeasurement> motions;
  LatticeResult lattice;
};

// Each place's heading in the lattice frame (the first place's heading along +x): stored
// headings when every place has one, else the relative headings measured between consecutive
// places (phases), integrated along the exploration; none for places that cannot be reached.
std::vector<std::optional<double>> lattice_headings(const memory::VisualMemory& memory);

// Calibrates, builds the springs and motion constraints, solves, and stores each place's
// lattice position (metres, lattice frame: place 0 at the origin, its heading along +x).
// Throws UsageError when the scale is unknown (no step given and none in the map) or the map
// has fewer than two places.
OrganiseResult organise(memory::VisualMemory& memory, const OrganiseParams& params);

}  // namespace omninav::lattice
