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
      : rank_(place_count),
        parent_(place_count),
        sets_(rank_.data(), parent_.data()),
        count_(place_count) {
    for (int place = 0; place < place_count; ++place) sets_.make_set(place);
  }
  PlaceSets(const PlaceSets&) = delete;
  PlaceSets& operator=(const PlaceSets&) = delete;

  void join(int a, int b) {
    const int root_a = sets_.find_set(a), root_b = sets_.find_set(b);
    if (root_a == root_b) return;
    sets_.link(root_a, root_b);
    --count_;
  }
  bool joined(int a, int b) { return sets_.find_set(a) == sets_.find_set(b); }
  int find(int a) { return sets_.find_set(a); }  // the set's representative
  int count() const { return count_; }           // sets left

 private:
  std::vector<int> rank_, parent_;
  boost::disjoint_sets<int*, int*> sets_;
  int count_;  // kept as sets are joined: counting the roots each time would be O(places)
};

}  // namespace omninav::lattice::detail
