// SPDX-License-Identifier: BSD-3-Clause
// The queues against an ordered set: the same cells come out in the same order, whatever
// sequence of inserts, key changes and removals came before.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <utility>
#include <vector>

#include "quad/planning/bucket_queue.hpp"
#include "quad/planning/indexed_heap.hpp"

namespace quad::planning {
namespace {

constexpr int kCells = 500;

/// Random operations on `queue` and on a reference set, checked after each; `queued(i)` tells
/// whether the queue's own record says cell i is queued.
template <typename Queue, typename Queued>
void checkAgainstOrderedSet(Queue& queue, Queued queued)
{
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
        queue.set(c, k);
        reference.insert({k, c});
        key_of[i] = k;
        break;
      }
      case 2:  // remove, queued or not
        queue.remove(c);
        if (key_of[i] >= 0) {
          reference.erase({key_of[i], c});
          key_of[i] = -1;
        }
        break;
      default:  // pop the least
        if (!reference.empty()) {
          const auto [k, least] = *reference.begin();
          ASSERT_EQ(queue.top().cell, least) << "operation " << op;
          ASSERT_EQ(queue.top().key, k);
          queue.pop();
          reference.erase(reference.begin());
          key_of[static_cast<std::size_t>(least)] = -1;
        }
    }
    ASSERT_EQ(queue.size(), reference.size());
  }
  // Every queued cell knows its place, every other one knows it is out.
  for (std::size_t i = 0; i < kCells; ++i) {
    EXPECT_EQ(queued(i), key_of[i] >= 0) << "cell " << i;
  }
  queue.clear();
  EXPECT_TRUE(queue.empty());
  for (std::size_t i = 0; i < kCells; ++i) {
    EXPECT_FALSE(queued(i)) << "cell " << i;
  }
}

struct Slots {
  std::vector<std::uint32_t>* slots;
  std::uint32_t& operator()(std::int64_t c) const { return (*slots)[static_cast<std::size_t>(c)]; }
};

TEST(IndexedHeap, PopsInKeyThenCellOrderAfterRandomInsertsKeyChangesAndRemovals)
{
  std::vector<std::uint32_t> slots(kCells, kNotQueued);
  IndexedHeap<int, Slots> heap(Slots{&slots});
  checkAgainstOrderedSet(heap, [&](std::size_t i) { return slots[i] != kNotQueued; });
}

struct Places {
  std::vector<QueuePlace>* places;
  QueuePlace& operator()(std::int64_t c) const { return (*places)[static_cast<std::size_t>(c)]; }
};

/// Buckets of seven keys: cells move between buckets and within them, and the lowest one
/// empties and fills again.
struct Sevens {
  std::uint32_t operator()(int key) const { return static_cast<std::uint32_t>(key / 7); }
};

TEST(BucketQueue, PopsInKeyThenCellOrderAfterRandomInsertsKeyChangesAndRemovals)
{
  std::vector<QueuePlace> places(kCells);
  BucketQueue<int, Places, Sevens> queue(Places{&places}, Sevens{});
  checkAgainstOrderedSet(queue, [&](std::size_t i) { return places[i].bucket != kNotQueued; });
}

struct OneBucket {
  std::uint32_t operator()(int) const { return 0; }
};

TEST(BucketQueue, ComesOutLikeOneHeapWhenEveryKeyIsInTheSameBucket)
{
  std::vector<QueuePlace> places(kCells);
  BucketQueue<int, Places, OneBucket> queue(Places{&places}, OneBucket{});
  checkAgainstOrderedSet(queue, [&](std::size_t i) { return places[i].bucket != kNotQueued; });
}

TEST(BucketQueue, AgedKeysComeOutInTheOrderOfTheirKeysNow)
{
  std::vector<QueuePlace> places(kCells);
  BucketQueue<int, Places, Sevens> queue(Places{&places}, Sevens{});
  std::vector<int> key_now(kCells);
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> key(0, 200);
  std::uniform_int_distribution<int> rise(0, 30);
  for (std::int64_t c = 0; c < kCells; ++c) {
    key_now[static_cast<std::size_t>(c)] = key(rng);
    queue.set(c, key_now[static_cast<std::size_t>(c)]);
  }
  const auto fresh = [&](const auto& entry) { return key_now[static_cast<std::size_t>(entry.cell)]; };
  for (int age = 0; age < 4; ++age) {
    // Every key rises by its own amount; the queue only hears that they aged.
    for (int& k : key_now) {
      k += rise(rng);
    }
    queue.keysAged();
    std::set<std::pair<int, std::int64_t>> reference;
    for (std::size_t i = 0; i < kCells; ++i) {
      if (places[i].bucket != kNotQueued) {
        reference.insert({key_now[i], static_cast<std::int64_t>(i)});
      }
    }
    // Take out a quarter in order, then queue them again with their keys now.
    std::vector<std::int64_t> taken;
    for (int n = 0; n < kCells / 4; ++n) {
      const auto [k, least] = *reference.begin();
      ASSERT_EQ(queue.top(fresh).cell, least) << "age " << age << ", pop " << n;
      ASSERT_EQ(queue.top(fresh).key, k);
      queue.pop();
      reference.erase(reference.begin());
      taken.push_back(least);
    }
    for (const std::int64_t c : taken) {
      queue.set(c, key_now[static_cast<std::size_t>(c)]);
    }
    ASSERT_EQ(queue.size(), static_cast<std::size_t>(kCells));
  }
}

}  // namespace
}  // namespace quad::planning
