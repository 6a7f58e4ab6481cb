// SPDX-License-Identifier: BSD-3-Clause
// ModuleWatch between two real participants: a module is unknown until its first heartbeat,
// alive while its heartbeat writer asserts liveliness, lost within the 0.5 s lease once it
// stops, and alive again when it resumes; another module's heartbeats say nothing of it. A
// LivelinessKeeper keeps a writer that writes nothing alive, until it goes.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <optional>
#include <thread>

#include "quad/common/time.hpp"
#include "quad/dds/liveliness.hpp"
#include "quad/dds/module_watch.hpp"
#include "quad/dds/participant.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/topics.hpp"
#include "side_by_side.hpp"
#include "wait.hpp"

namespace quad::dds {
namespace {

constexpr int kDomain = 167;        // this test's own
constexpr int kKeeperDomain = 82;   // and the keeper's

msg::Heartbeat heartbeat(const std::string& module)
{
  msg::Heartbeat hb;
  hb.module_name(module);
  hb.host("test");
  hb.pid(1);
  hb.state(msg::MODULE_RUNNING);
  return hb;
}

TEST(ModuleWatch, FollowsTheHeartbeatWritersLiveliness)
{
  Participant module(test::sideBySide("module", kDomain));
  Participant watcher(test::sideBySide("watcher", kDomain));
  Publisher<msg::Heartbeat> mapping(module, topics::kHeartbeat);
  Publisher<msg::Heartbeat> plant(module, topics::kHeartbeat);
  ModuleWatch watch(watcher, "mapping", nullptr);
  ASSERT_TRUE(test::waitFor([&] { return mapping.matchedReaders() == 1 && plant.matchedReaders() == 1; }));
  // The lease it tells its users (the planner's lockstep grace) is the one the writers offer.
  EXPECT_EQ(watch.leaseNs(), std::optional<std::int64_t>(500'000'000));
  EXPECT_EQ(mapping.livelinessLeaseNs(), watch.leaseNs());

  // Another module's heartbeats, however alive, leave it unknown.
  ASSERT_TRUE(plant.write(heartbeat("plant")));
  EXPECT_FALSE(test::waitFor([&] { return watch.update() != ModuleWatch::State::kUnknown; },
                             std::chrono::milliseconds(300)));

  ASSERT_TRUE(mapping.write(heartbeat("mapping")));
  ASSERT_TRUE(test::waitFor([&] { return watch.update() == ModuleWatch::State::kAlive; }));

  // Kept alive by assertions alone (what a node's liveliness thread does while it is busy).
  const std::int64_t until = common::steadyTimeNs() + 1'200'000'000;
  while (common::steadyTimeNs() < until) {
    mapping.assertLiveliness();
    plant.assertLiveliness();
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ASSERT_EQ(watch.update(), ModuleWatch::State::kAlive);
  }

  // Silent (stopped): lost within the lease, though the plant's writer goes on.
  const std::int64_t stopped = common::steadyTimeNs();
  ASSERT_TRUE(test::waitFor([&] {
    plant.assertLiveliness();
    return watch.update() == ModuleWatch::State::kLost;
  }));
  const double noticed_s = common::toSeconds(common::steadyTimeNs() - stopped);
  EXPECT_GT(noticed_s, 0.3) << "lost before the 0.5 s lease ended";
  EXPECT_LT(noticed_s, 1.0) << "the lease is 0.5 s";

  // Resumed.
  mapping.assertLiveliness();
  EXPECT_TRUE(test::waitFor([&] { return watch.update() == ModuleWatch::State::kAlive; }));
}

TEST(LivelinessKeeper, KeepsAWriterThatWritesNothingAliveUntilItGoes)
{
  Participant module(test::sideBySide("module", kKeeperDomain));
  Participant watcher(test::sideBySide("watcher", kKeeperDomain));
  Publisher<msg::Heartbeat> mapping(module, topics::kHeartbeat);
  ModuleWatch watch(watcher, "mapping", nullptr);
  ASSERT_TRUE(test::waitFor([&] { return mapping.matchedReaders() == 1; }));
  auto keeper = std::make_unique<LivelinessKeeper>(mapping);
  ASSERT_TRUE(mapping.write(heartbeat("mapping")));
  ASSERT_TRUE(test::waitFor([&] { return watch.update() == ModuleWatch::State::kAlive; }));

  // Three leases without a sample (a sim-time writer while the clock stands): still alive.
  const std::int64_t until = common::steadyTimeNs() + 1'500'000'000;
  while (common::steadyTimeNs() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_EQ(watch.update(), ModuleWatch::State::kAlive);
  }

  // The keeper gone (its process stopped): lost within the lease.
  keeper.reset();
  EXPECT_TRUE(test::waitFor([&] { return watch.update() == ModuleWatch::State::kLost; },
                            std::chrono::milliseconds(1500)));
}

}  // namespace
}  // namespace quad::dds
