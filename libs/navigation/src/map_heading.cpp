#include "omninav/navigation/map_heading.hpp"

#include <cmath>
#include <limits>

#include "omninav/core/angles.hpp"
#include "omninav/navigation/memory_places.hpp"

namespace omninav::navigation {

MapHeadings::MapHeadings(const memory::VisualMemory& memory,
                         const memory::LocalisationParams& localisation)
    : localiser_(memory, localisation),
      extractor_(memory.parameters().signature),
      limit_(recognition_limit(memory)) {}

std::optional<MapHeading> MapHeadings::measure(const cv::Mat& panorama) {
  const memory::Localisation localisation = memory_localiser(localiser_, extractor_)(panorama);
  if (localisation.best.empty()) return std::nullopt;
  const memory::PlaceMatch& best = localisation.best.front();
  if (!best.heading_rad || !(best.dissimilarity_per_value <= limit_)) return std::nullopt;
  MapHeading heading{best.place, *best.heading_rad, 0.0, best.dissimilarity_per_value};
  double squares = 0.0;
  int others = 0;
  for (std::size_t i = 1; i < localisation.best.size(); ++i) {
    const memory::PlaceMatch& other = localisation.best[i];
    if (!other.heading_rad || !(other.dissimilarity_per_value <= limit_)) continue;
    const double difference = signed_difference(*other.heading_rad, heading.heading_rad);
    squares += difference * difference;
    ++others;
  }
  heading.spread_rad =
      others > 0 ? std::sqrt(squares / others) : std::numeric_limits<double>::infinity();
  return heading;
}

bool realigns(const MapHeading& reading, double heading_rad, double sigma_rad, bool in_map_frame,
              const RealignmentParams& params) {
  if (!std::isfinite(reading.spread_rad)) return false;
  if (!in_map_frame) return true;
  const double innovation_rad = std::abs(signed_difference(reading.heading_rad, heading_rad));
  return reading.spread_rad < sigma_rad &&
         innovation_rad <= params.gate_sigmas * std::hypot(sigma_rad, reading.spread_rad);
}

}  // namespace omninav::navigation
