// SPDX-License-Identifier: BSD-3-Clause
// The queue against an ordered set: the same cells come out in the same order, whatever
// sequence of inserts, key changes and removals came before.
#include "quad/planning/indexed_heap.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <utility>
#include <vector>

namespace quad::planning {
namespace {

struct Slots {
  std::vector<std::uint32_t>* slots;
  std::uint32_t& operator()(std::int64_t c) const { return (*slots)[static_cast<std::size_t>(c)]; }
};

TEST(IndexedHeap, PopsInKeyThenCellOrderAfterRandomInsertsKeyChangesAndRemovals)
{
  constexpr int kCells = 500;
  std::vector<std::uint32_t> slots(kCells, kNotQueued);
  IndexedHeap<int, Slots> heap(Slots{&slots});
  std::set<std::pair<int, std::int64_t>> reference;  // (key, cell)
  std::vector<int> key_of(kCells, -1);             // -1: not queued
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<std::int64_t> cell(0, kCells - 1);
  std::uniform_int_distribution<int> key(0, 40);  // few keys: many ties, broken by cell
  for (int op = 0; op < 20000; ++op) {
    const std::int64_t c = cell(rng);
    const auto i = static_cast<std::size_t>(c);
    switch (rng() % 4) {
      case 0:
      case 1: {  // queue or change the key, up or down
        const int k = key(rng);
        if (key_of[i] >= 0) {
          reference.erase({key_of[i], c});
        }
        heap.set(c, k);
        reference.insert({k, c});
        key_of[i] = k;
        break;
      }
      case 2:  // remove, queued or not
        heap.remove(c);
        if (key_of[i] >= 0) {
          reference.erase({key_of[i], c});
          key_of[i] = -1;
        }
        break;
      default:  // pop the least
        if (!reference.empty()) {
          const auto [k, least] = *reference.begin();
          ASSERT_EQ(heap.top().cell, least) << "operation " << op;
          ASSERT_EQ(heap.top().key, k);
          heap.pop();
          reference.erase(reference.begin());
          key_of[static_cast<std::size_t>(least)] = -1;
        }
    }
    ASSERT_EQ(heap.size(), reference.size());
  }
  // Every queued cell knows its place, every other one knows it is out.
  for (std::size_t i = 0; i < slots.size(); ++i) {
    EXPECT_EQ(slots[i] != kNotQueued, key_of[i] >= 0) << "cell " << i;
  }
  heap.clear();
  EXPECT_TRUE(heap.empty());
  for (const std::uint32_t s : slots) {
    EXPECT_EQ(s, kNotQueued);
  }
}

}  // namespace
}  // namespace quad::planning
