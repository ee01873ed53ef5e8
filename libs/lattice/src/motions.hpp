#pragma once
// The motions of the lattice (Menegatti et al. 2004, §3.4): which pairs of places get one, what
// each measures and how far it is trusted.
//
// Every motion is the direction from one place to another fitted on the two signatures both
// ways (signature/motion.hpp) with the turn between them held at the difference of their
// headings, and a length. Three kinds of pair, in this order:
//   - steps: the consecutive places of a stream (edges of kind sequence). The robot went from
//     one to the other, so they are one exploration step apart however alike they look: beyond
//     the linear range of Fig. 7 (a 60 cm zig-zag), they look no nearer than far places.
//     Trusted: their length is the step, held tightly, and the lattice's start is built on them
//     (initial_positions.cpp).
//   - listed pairs: consecutive images of an unordered input (edges of kind listed, a grid
//     database), when they look one step apart (step_likeness): a raster's row ends do not.
//   - neighbours: each place and its most similar places, the length from the calibration,
//     held loosely. Some are look-alikes metres away (periodic rooms, 60 cm spacings), with a
//     direction anywhere; their fits explain the two views worse (measured on five rendered
//     maps: residuals of truly near pairs median 0.38-0.70 of the signal, look-alikes above
//     1.0), so a neighbour motion whose fit leaves more than look_alike_residual times the map's
//     median residual is dropped; and so is one between places of a stream at most
//     step_check_steps apart that disagrees with the steps between them by more than
//     step_check_sigmas standard deviations (dead reckoning over a few steps is better than any
//     look-alike). The three numbers are chosen across the zoo (docs/evaluation.md,
//     "Thresholds across the zoo").
// Last, places that these motions leave apart are joined by the most similar pairs across, even
// look-alikes (a lattice in pieces held by springs alone falls apart: a piece whose motions were
// all dropped drifts away, pushed by its one-sided springs).

#include <vector>

#include "omninav/lattice/organise.hpp"
#include "omninav/lattice/similar_places.hpp"

namespace omninav::lattice::detail {

struct MeasuredMotions {
  std::vector<MotionMeasurement> motions;
  int look_alikes_dropped = 0;  // neighbour motions dropped (residual, or against the steps)
  int joins = 0;                // motions added to join places the others left apart
  int pieces = 1;               // how many pieces the checked motions left the places in
};

MeasuredMotions measure_motions(const memory::VisualMemory& memory,
                                const PlaceDissimilarities& dissimilarity,
                                const std::vector<std::vector<SimilarPlace>>& ranking,
                                const DistanceCalibration& calibration,
                                const OrganiseParams& params);

}  // namespace omninav::lattice::detail
