#pragma once
// Scoring a localisation (memory/localisation.hpp) against ground truth.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "omninav/core/pose.hpp"
#include "omninav/memory/localisation.hpp"
#include "omninav/memory/visual_memory.hpp"

namespace omninav::evaluation {

// Localisation against ground truth (docs/design.md, Evaluation): the share of queries whose best
// place lies within one grid spacing of the truth; per level, the share whose candidate set
// contains the true nearest place and the mean size of the set; and the query heading's error
// when places have headings. Queries "between the grid points" are scored: those within half a
// cell's diagonal (spacing·√2/2) of a place. Others lie beyond the grid's edge or in a hole
// of it (furniture), where the nearest place can be a whole spacing away and its neighbours
// farther: they are counted apart and not scored.
class LocalisationScore {
 public:
  // `memory`'s places must all have ground truth (UsageError otherwise).
  explicit LocalisationScore(const memory::VisualMemory& memory);

  struct Query {
    memory::PlaceIndex nearest_place = 0;  // the place nearest the truth
    double nearest_m = 0.0;
    double error_m = 0.0;  // from the best place to the truth
    bool within_spacing = false;
    std::vector<bool> level_contains_nearest;
    std::optional<double> heading_error_rad;
    bool outside = false;  // farther than spacing·√2/2 from every place: not scored
  };
  Query add(const memory::Localisation& result, const CameraPose& truth);

  std::size_t queries() const { return queries_; }  // scored ones
  std::size_t outside() const { return outside_; }
  double spacing_m() const { return spacing_m_; }
  double within_spacing_share() const;
  double nearest_share() const;  // the best place is the place nearest the truth
  double mean_error_m() const;   // from the best place to the truth
  std::vector<double> level_contains_share() const;
  std::vector<double> level_mean_size() const;
  // Median |heading error|, when any query had one.
  std::optional<double> median_heading_error_rad() const;
  // Lines like "localised 120 queries: 99.2% within one spacing (0.30 m) ...".
  std::string summary(const std::vector<int>& levels) const;

 private:
  std::vector<Eigen::Vector2d> places_;  // true positions
  double spacing_m_ = 1.0;
  std::size_t queries_ = 0;
  std::size_t outside_ = 0;
  std::size_t within_ = 0;
  std::size_t nearest_ = 0;
  double error_sum_m_ = 0.0;
  std::vector<std::size_t> contains_;
  std::vector<double> size_sum_;
  std::vector<double> heading_errors_;
};

}  // namespace omninav::evaluation
