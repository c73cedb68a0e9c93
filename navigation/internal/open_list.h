// The open list of the planner's searches: an indexed 4-ary min-heap.
#ifndef FOGNAV_NAVIGATION_INTERNAL_OPEN_LIST_H_
#define FOGNAV_NAVIGATION_INTERNAL_OPEN_LIST_H_

#include <algorithm>
#include <cstdint>
#include <vector>

namespace fognav::navigation::internal {

// open-list entry: smallest f first, ties broken toward larger g (deeper)
struct OpenEntry {
  double f;
  float g;  // only breaks ties
  int32_t state;
};

// An indexed 4-ary min-heap holding each state at most once, so an improved
// state moves up in place instead of leaving a stale copy behind. Storage is borrowed, reused
// from search to search.
class OpenList {
 public:
  // Starts empty, or with `clear` false, with the entries already in `heap`.
  OpenList(std::vector<OpenEntry>* heap, std::vector<int32_t>* position, bool clear = true)
      : heap_(*heap), position_(*position) {
    if (clear) heap_.clear();
  }
  bool empty() const { return heap_.empty(); }
  // Inserts e, or if its state is already `queued`, lowers that state's key to e's.
  void Push(const OpenEntry& e, bool queued) {
    size_t i = heap_.size();
    if (queued) {
      i = size_t(position_[size_t(e.state)]);
    } else {
      heap_.push_back(e);
    }
    SiftUp(i, e);
  }
  OpenEntry Pop() {
    const OpenEntry top = heap_.front();
    const OpenEntry last = heap_.back();
    heap_.pop_back();
    if (!heap_.empty()) SiftDown(0, last);
    return top;
  }

 private:
  static bool Before(const OpenEntry& a, const OpenEntry& b) {
    return a.f < b.f || (a.f == b.f && a.g > b.g);
  }
  void Place(size_t i, const OpenEntry& e) {
    heap_[i] = e;
    position_[size_t(e.state)] = int32_t(i);
  }
  void SiftUp(size_t i, const OpenEntry& e) {
    while (i > 0) {
      const size_t parent = (i - 1) / 4;
      if (!Before(e, heap_[parent])) break;
      Place(i, heap_[parent]);
      i = parent;
    }
    Place(i, e);
  }
  void SiftDown(size_t i, const OpenEntry& e) {
    const size_t n = heap_.size();
    while (true) {
      const size_t first = 4 * i + 1;
      if (first >= n) break;
      size_t best = first;
      for (size_t j = first + 1; j < std::min(first + 4, n); ++j) {
        if (Before(heap_[j], heap_[best])) best = j;
      }
      if (!Before(heap_[best], e)) break;
      Place(i, heap_[best]);
      i = best;
    }
    Place(i, e);
  }

  std::vector<OpenEntry>& heap_;
  std::vector<int32_t>& position_;
};

}  // namespace fognav::navigation::internal

#endif  // FOGNAV_NAVIGATION_INTERNAL_OPEN_LIST_H_
