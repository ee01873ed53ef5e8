#include "omninav/evaluation/organised_map.hpp"

#include <string>

#include "omninav/core/errors.hpp"

namespace omninav::evaluation {

OrganisedMap organise_stored_map(memory::MapStore& store, const lattice::OrganiseParams& params) {
  OrganisedMap result{store.load(), {}, std::nullopt};
  result.organised = lattice::organise(result.memory, params);
  for (std::size_t i = 0; i < result.memory.place_count(); ++i) {
    if (!result.memory.place(i).lattice_position->allFinite()) {
      throw InputError(store.file().string() + ": the lattice has no finite position for place " +
                       std::to_string(i) + "; the map is left unchanged");
    }
  }
  result.score = score_lattice(result.memory, result.organised.motions.empty());
  return result;
}

}  // namespace omninav::evaluation
