// The indexed 4-ary heap of the bounding mesh queue: under random pushes, key changes in both
// directions and erasures it pops in the order of a sorted reference, ties broken by id.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <utility>
#include <vector>

#include "kaboum/geometry/indexed_heap.hpp"

namespace kaboum::geometry {
namespace {

TEST(IndexedMinHeap, MatchesASortedReferenceUnderRandomUpdates) {
  constexpr std::uint32_t kIds = 500;
  std::mt19937 random(7);
  std::uniform_int_distribution<std::uint32_t> pickId(0, kIds - 1);
  std::uniform_int_distribution<int> pickKey(0, 40);  // few distinct keys: many ties
  std::uniform_int_distribution<int> pickAction(0, 9);
  IndexedMinHeap heap;
  heap.reset(kIds);
  std::set<std::pair<double, std::uint32_t>> reference;
  std::vector<double> keyOf(kIds, 0.0);
  std::vector<bool> queued(kIds, false);
  for (int step = 0; step < 200000; ++step) {
    const int action = pickAction(random);
    if (action < 6) {  // queue or move an id, up or down
      const std::uint32_t id = pickId(random);
      const double key = pickKey(random);
      if (queued[id]) reference.erase({keyOf[id], id});
      heap.set(id, key);
      reference.insert({key, id});
      keyOf[id] = key;
      queued[id] = true;
    } else if (action < 8) {  // erase an id, queued or not
      const std::uint32_t id = pickId(random);
      heap.erase(id);
      if (queued[id]) reference.erase({keyOf[id], id});
      queued[id] = false;
    } else if (!reference.empty()) {  // pop
      ASSERT_EQ(heap.top(), reference.begin()->second);
      ASSERT_EQ(heap.topKey(), reference.begin()->first);
      queued[heap.top()] = false;
      heap.erase(heap.top());
      reference.erase(reference.begin());
    }
    ASSERT_EQ(heap.size(), reference.size());
  }
  for (std::uint32_t id = 0; id < kIds; ++id) {
    ASSERT_EQ(heap.contains(id), static_cast<bool>(queued[id]));
    if (queued[id]) {
      EXPECT_EQ(heap.key(id), keyOf[id]);
    }
  }
  while (!reference.empty()) {
    ASSERT_EQ(heap.top(), reference.begin()->second);
    heap.erase(heap.top());
    reference.erase(reference.begin());
  }
  EXPECT_TRUE(heap.empty());
}

}  // namespace
}  // namespace kaboum::geometry
