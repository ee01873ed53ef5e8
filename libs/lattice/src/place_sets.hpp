#pragma once
// Places grouped into connected sets as links are added (union-find): Boost's disjoint_sets over
// two arrays, for the motions that must hold every place (motions.cpp) and for the stretches of
// a stream that its steps alone already place (initial_positions.cpp).

#include <boost/pending/disjoint_sets.hpp>
#include <vector>

namespace omninav::lattice::detail {

class PlaceSets {
 public:
  explicit PlaceSets(int place_count)
      : rank_(place_count), parent_(place_count), sets_(rank_.data(), parent_.data()) {
    for (int place = 0; place < place_count; ++place) sets_.make_set(place);
  }
  PlaceSets(const PlaceSets&) = delete;
  PlaceSets& operator=(const PlaceSets&) = delete;

  void join(int a, int b) { sets_.union_set(a, b); }
  bool joined(int a, int b) { return sets_.find_set(a) == sets_.find_set(b); }
  int count() { return static_cast<int>(sets_.count_sets(parent_.begin(), parent_.end())); }

 private:
  std::vector<int> rank_, parent_;
  boost::disjoint_sets<int*, int*> sets_;
};

}  // namespace omninav::lattice::detail
