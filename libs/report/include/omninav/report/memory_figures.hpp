#pragma once
// Pictures of the visual memory, after the figures of Menegatti et al. 2004:
//   - Figs. 8-10, a localisation: every place at its position (lattice, else ground truth),
//     coloured by its similarity to the query at each level, the candidate set shaded;
//   - Figs. 5-7 from a map of a grid with ground truth, whose source images are read again:
//     a row's spectrum (Fig. 5), similarity to nearby places against the number of components
//     (Fig. 6) with the leave-one-out localisation rate against it, and dissimilarity against
//     distance (Fig. 7). docs/memory.md shows them with the commands that make them.

#include <Eigen/Core>
#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "omninav/memory/localisation.hpp"
#include "omninav/memory/visual_memory.hpp"

namespace omninav::report {

// One panel per level, side by side: places as discs coloured by Eq. 3's similarity at that
// level over all places (dark blue 0 .. yellow 1000, OpenCV's viridis), the candidate set of
// `result` shaded grey under them, the best place ringed, the position estimate as a black
// diamond and `query_position` (the query's true position, when known, in the frame of the
// places' positions) as a red cross. Throws UsageError when the map has no positions (no
// lattice, no ground truth).
cv::Mat localisation_figure(const memory::Localiser& localiser, const signature::Signature& query,
                            const memory::Localisation& result,
                            std::optional<Eigen::Vector2d> query_position,
                            const std::string& title);

struct SignatureFigures {
  std::vector<std::filesystem::path> files;  // PNG and CSV files written
  std::string summary;                       // a few lines of numbers for the docs
};

// Writes fig5_spectrum, fig6_components, fig6_localisation_rate and fig7_dissimilarity_distance
// (.png, with their data as .csv) into `folder`. The map's places must have ground truth and
// source images that can still be read (the explore command stores absolute paths). Throws
// UsageError otherwise.
SignatureFigures write_signature_figures(const memory::VisualMemory& memory,
                                         const std::filesystem::path& folder);

}  // namespace omninav::report
