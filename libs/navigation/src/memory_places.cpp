#include "omninav/navigation/memory_places.hpp"

#include <algorithm>
#include <limits>

#include "omninav/core/errors.hpp"
#include "omninav/lattice/organise.hpp"

namespace omninav::navigation {

std::vector<PlaceNode> places_from_memory(const memory::VisualMemory& memory) {
  if (memory.place_count() == 0) throw UsageError("the map has no places");
  if (!memory.all_have_lattice()) {
    throw UsageError("the map has no lattice yet: run 'omninav organise' on it first");
  }
  const std::vector<std::optional<double>> headings = lattice::lattice_headings(memory);
  std::vector<PlaceNode> places;
  for (std::size_t i = 0; i < memory.place_count(); ++i) {
    if (!headings[i]) {
      throw UsageError("place " + std::to_string(i) +
                       " has no heading, stored or measured along the exploration: the navigator "
                       "cannot tell the robot which way to turn there");
    }
    const memory::LatticePosition& position = *memory.place(i).lattice;
    places.push_back({Eigen::Vector2d(position.x, position.y), *headings[i]});
  }
  return places;
}

double lattice_spacing(const std::vector<PlaceNode>& places) {
  if (places.size() < 2) return 1.0;
  std::vector<double> nearest;
  for (std::size_t i = 0; i < places.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < places.size(); ++j) {
      if (i != j) best = std::min(best, (places[i].position_m - places[j].position_m).norm());
    }
    nearest.push_back(best);
  }
  std::nth_element(nearest.begin(), nearest.begin() + nearest.size() / 2, nearest.end());
  return nearest[nearest.size() / 2];
}

Localiser memory_localiser(const memory::Localiser& localiser,
                           signature::SignatureExtractor& extractor) {
  return [&localiser, &extractor](const cv::Mat& panorama) {
    const memory::Localisation result =
        localiser.localise(extractor.compute(panorama, "the robot's view"));
    PlaceMatch match;
    if (result.best.empty()) return match;
    match.place = static_cast<int>(result.best.front().place);
    match.similarity = result.best.front().similarity;
    match.heading_in_place_rad = result.best.front().relative_heading_rad;
    return match;
  };
}

}  // namespace omninav::navigation
