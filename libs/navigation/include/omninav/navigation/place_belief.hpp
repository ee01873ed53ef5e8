#pragma once
// A belief over the map's places, carried from view to view: a discrete Bayes filter (a hidden
// Markov model over the memory graph, as Markov localisation over a topological map: Simmons &
// Koenig 1995, Fox, Burgard & Thrun 1999). Each step:
//   - predict: the motion the robot made moves each place's probability along its links whose
//     direction agrees with the motion (seen from that place: the robot's heading relative to
//     the place's image, from the phases, plus the turn it made), in proportion to the distance
//     driven over the link's length; the rest stays;
//   - update: each place's probability times the likelihood of the view there,
//     exp(−(d_p − d_min) / τ), d_p the view's mean dissimilarity per value to place p (Eq. 6)
//     and τ the map's typical dissimilarity between linked places (one spacing apart): a view
//     one spacing farther from a place than from the best is e times less likely there.
// A view that looks like two places far apart (look-alikes) splits the belief; the motion that
// follows tells which was right, where the single best match of one view cannot. The place the
// robot acts on is the most probable. Lost means the belief is spread: less than a given share
// of it lies on the most probable place and the places linked to it.

#include <span>
#include <vector>

#include "omninav/navigation/route_planner.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::navigation {

struct BeliefParams {
  // τ in units of the median dissimilarity per value of the map's confirmed links.
  double view_scale = 1.0;
  // How far (degrees, standard deviation) the robot's motion may point from a link's direction
  // and still carry probability along it.
  double direction_sigma_deg = 45.0;
  // Each prediction mixes this share of a uniform belief in: the robot may be anywhere with a
  // small probability (it was carried off, or the map's links miss where it drove).
  double uniform_share = 1e-3;
  // Confident: at least this much of the belief on the most probable place and the places
  // linked to it (the robot stands somewhere between them); lost otherwise.
  double confident_share = 0.5;

  // The ranges of navigation.yaml's belief section. Throws UsageError naming the key
  // (core/param_check.hpp); the loader and PlaceBelief's constructor call it.
  void check() const;
};

// Reads the `belief:` section of navigation.yaml.
void load_belief_params(const ConfigReader& section, BeliefParams& params);

class PlaceBelief {
 public:
  // Uniform over `place_count` places linked by `links`; `view_scale_per_value` is τ.
  PlaceBelief(std::size_t place_count, std::vector<MeasuredLink> links, double view_scale_per_value,
              const BeliefParams& params);

  // The robot drove `distance_m` in the direction motion_in_place_rad[p] relative to place p's
  // heading, were it at p (NaN: unknown there; the probability stays).
  void predict(std::span<const double> motion_in_place_rad, double distance_m);
  // The view's dissimilarity per value to every place.
  void update(std::span<const double> dissimilarity_per_value);

  int most_likely() const;
  double probability(int place) const { return probability_[place]; }
  const std::vector<double>& probabilities() const { return probability_; }
  // The probability on `place` and the places linked to it.
  double neighbourhood_probability(int place) const;
  bool lost() const { return neighbourhood_probability(most_likely()) < params_.confident_share; }
  // Forgets the link between a and b (the robot found it blocked).
  void remove_link(int a, int b);
  // Every link it was made with again.
  void restore_links();

 private:
  void index_links();

  std::vector<MeasuredLink> links_;
  std::vector<std::vector<std::size_t>> links_of_;  // each place's links (indices in links_)
  double view_scale_;
  BeliefParams params_;
  std::vector<double> probability_;
};

}  // namespace omninav::navigation
