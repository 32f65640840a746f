// A 4-ary min-heap of (key, id) with a position index per id, so a queued id's key can be raised or
// lowered in place: the edge queue of Algorithm 2 (thesis §4.3) with lazily solved candidates.
// Ties break on the id, so the order is total and the pop sequence does not depend on the order of
// insertions and updates.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace kaboum::geometry {

class IndexedMinHeap {
 public:
  // Empties the heap and accepts ids 0 … idCount-1.
  void reset(std::size_t idCount) {
    entries_.clear();
    positions_.assign(idCount, kAbsent);
  }
  [[nodiscard]] bool empty() const { return entries_.empty(); }
  [[nodiscard]] std::size_t size() const { return entries_.size(); }
  [[nodiscard]] bool contains(std::uint32_t id) const { return positions_[id] != kAbsent; }
  [[nodiscard]] std::uint32_t top() const { return entries_.front().id; }
  [[nodiscard]] double topKey() const { return entries_.front().key; }
  [[nodiscard]] double key(std::uint32_t id) const { return entries_[positions_[id]].key; }

  // Queues `id` with `key`, or moves it to `key` if it is queued already.
  void set(std::uint32_t id, double key) {
    if (!contains(id)) {
      positions_[id] = static_cast<std::uint32_t>(entries_.size());
      entries_.push_back({key, id});
      siftUp(entries_.size() - 1);
      return;
    }
    const std::size_t at = positions_[id];
    const Entry old = entries_[at];
    entries_[at].key = key;
    if (before(entries_[at], old)) {
      siftUp(at);
    } else {
      siftDown(at);
    }
  }

  // Removes `id` if it is queued.
  void erase(std::uint32_t id) {
    if (!contains(id)) return;
    const std::size_t at = positions_[id];
    positions_[id] = kAbsent;
    const Entry last = entries_.back();
    entries_.pop_back();
    if (at == entries_.size()) return;
    entries_[at] = last;
    positions_[last.id] = static_cast<std::uint32_t>(at);
    if (at > 0 && before(last, entries_[(at - 1) / kArity])) {
      siftUp(at);
    } else {
      siftDown(at);
    }
  }

 private:
  struct Entry {
    double key;
    std::uint32_t id;
  };
  static constexpr std::uint32_t kAbsent = 0xffffffffu;
  static constexpr std::size_t kArity = 4;

  static bool before(const Entry& l, const Entry& r) {
    return l.key < r.key || (l.key == r.key && l.id < r.id);
  }
  void place(std::size_t at, const Entry& e) {
    entries_[at] = e;
    positions_[e.id] = static_cast<std::uint32_t>(at);
  }
  void siftUp(std::size_t at) {
    const Entry moving = entries_[at];
    while (at > 0) {
      const std::size_t parent = (at - 1) / kArity;
      if (!before(moving, entries_[parent])) break;
      place(at, entries_[parent]);
      at = parent;
    }
    place(at, moving);
  }
  void siftDown(std::size_t at) {
    const Entry moving = entries_[at];
    const std::size_t n = entries_.size();
    for (;;) {
      const std::size_t first = kArity * at + 1;
      if (first >= n) break;
      std::size_t best = first;
      const std::size_t end = first + kArity < n ? first + kArity : n;
      for (std::size_t c = first + 1; c < end; ++c) {
        if (before(entries_[c], entries_[best])) best = c;
      }
      if (!before(entries_[best], moving)) break;
      place(at, entries_[best]);
      at = best;
    }
    place(at, moving);
  }

  std::vector<Entry> entries_;
  std::vector<std::uint32_t> positions_;  // index in entries_ per id, kAbsent when not queued
};

}  // namespace kaboum::geometry
