#pragma once
// The k best of a stream of items, in one pass: a heap of at most k items whose top is the
// worst kept, so that each offer costs O(log k) and only a better item replaces it.

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace omninav {

// `Better` is a strict weak order, better(a, b) when a ranks before b; break ties in it (by an
// index, say) for a result that does not depend on the order of the offers' equals.
template <typename T, typename Better>
class BestK {
 public:
  BestK(std::size_t k, Better better) : k_(k), better_(std::move(better)) {}

  void reserve() { heap_.reserve(k_ + 1); }

  void offer(const T& item) {
    if (heap_.size() < k_) {
      heap_.push_back(item);
      std::push_heap(heap_.begin(), heap_.end(), better_);
    } else if (k_ > 0 && better_(item, heap_.front())) {
      std::pop_heap(heap_.begin(), heap_.end(), better_);
      heap_.back() = item;
      std::push_heap(heap_.begin(), heap_.end(), better_);
    }
  }

  // The kept items, best first.
  std::vector<T> take_sorted() && {
    std::sort_heap(heap_.begin(), heap_.end(), better_);
    return std::move(heap_);
  }

 private:
  std::size_t k_;
  Better better_;
  std::vector<T> heap_;
};

}  // namespace omninav
