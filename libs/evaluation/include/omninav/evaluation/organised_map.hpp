#pragma once
// What `omninav organise` and `omninav evaluate` do to a stored map.

#include <optional>

#include "omninav/evaluation/lattice_score.hpp"
#include "omninav/lattice/organise.hpp"
#include "omninav/memory/map_store.hpp"
#include "omninav/memory/visual_memory.hpp"

namespace omninav::evaluation {

struct OrganisedMap {
  memory::VisualMemory memory;  // with its lattice positions
  lattice::OrganiseResult organised;
  std::optional<LatticeScore> score;  // when the places have ground truth
};

// Loads the map from `store`, organises it with `params` and scores the lattice against the
// truth when the places have it (reflection allowed when no motion constrained the lattice).
// It does not write: the caller saves `memory` to `store` last, after whatever else may fail
// (the picture), so that a failure leaves the map as it was. Throws InputError when a position
// is not finite.
OrganisedMap organise_stored_map(memory::MapStore& store, const lattice::OrganiseParams& params);

}  // namespace omninav::evaluation
