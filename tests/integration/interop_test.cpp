// SPDX-License-Identifier: BSD-3-Clause
// Another DDS implementation on quad's topics: a Cyclone DDS program built from quad's IDL
// (tests/support/cyclone_peer.c) joins a running stack, decodes the vehicle state to the same
// values quad's own subscriber sees, and gives a goal that the stack flies to. Domain 232.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "json_lines.hpp"
#include "process.hpp"
#include "scratch.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;
namespace fs = std::filesystem;

TEST(Interop, ACycloneDdsPeerReadsTheStateAndGivesAGoalTheStackFlies)
{
#ifndef QUAD_CYCLONE_PEER
  GTEST_SKIP() << "Cyclone DDS (cyclonedds-dev, cyclonedds-tools) was not found when quad was configured; "
                  "tools/setup.sh test installs it";
#else
  const fs::path dir = quad::test::scratchDir("quad_interop");
  const std::string root = QUAD_SOURCE_DIR;
  // The five modules, no mission of the launcher's: the goal comes from the other vendor.
  std::ofstream(dir / "m.yaml") << "name: interop\nworld: " << root << R"(/configs/worlds/open.yaml
mode: lockstep
transport: udp
modules:
  mapping: {config: )" << root << R"(/configs/mapping.yaml, set: {world: "${world}"}}
  planning: {config: )" << root << R"(/configs/planning.yaml, set: {world: "${world}"}, needs: [quad/mapping/update]}
  estimation: {config: )" << root << R"(/configs/estimation.yaml}
  control: {config: )" << root << R"(/configs/control.yaml, needs: [quad/planning/path]}
  plant:
    config: )" << root << R"(/configs/plant.yaml
    set: {world: "${world}", sim.mode: lockstep, sim.duration: 300.0, lockstep.participants: "mapping,planning"}
    needs: [quad/control/actuators, quad/mapping/update, quad/sim/lockstep]
)";
  const std::map<std::string, std::string> env{{"QUAD_DOMAIN_ID", "232"}, {"QUAD_TRANSPORT", "udp"}};
  ChildProcess launch({QUAD_TOOL, "launch", (dir / "m.yaml").string(), "--domain", "232", "--quiet", "--log-dir",
                       (dir / "run").string()});
  ChildProcess ours({QUAD_TOOL, "topic", "echo", "quad/sim/state", "--json"}, env);
  // WHEN the peer gives the goal (12, 4, 3)
  ChildProcess peer({QUAD_CYCLONE_PEER, "232", "12", "4", "3", "150"});
  // THEN the vehicle gets there, as the peer's own decoding of the state says
  // (our echo's output is read meanwhile: a full pipe would stop it printing)
  std::optional<int> reached;
  for (auto left = 170s; !reached && left > 0s; left -= 1s) {
    reached = peer.wait(1s);
    ours.output();
  }
  ASSERT_TRUE(reached) << peer.output();
  EXPECT_EQ(*reached, 0) << peer.output() << launch.output();
  // AND the peer decoded every state it got to the values quad's subscriber printed
  std::map<std::uint64_t, nlohmann::json> seen;
  for (const auto& s : quad::test::jsonLines(ours.output())) {
    seen[s["header"]["seq"].get<std::uint64_t>()] = s;
  }
  int compared = 0;
  for (const auto& theirs : quad::test::jsonLines(peer.output())) {
    const auto it = seen.find(theirs["header"]["seq"].get<std::uint64_t>());
    if (it == seen.end()) {
      continue;
    }
    const auto& q = it->second;
    ++compared;
    EXPECT_EQ(theirs["header"]["stamp_ns"], q["header"]["stamp_ns"]);
    for (const char* field : {"p_W", "v_W", "q_WB"}) {
      for (const auto& [axis, value] : theirs[field].items()) {
        EXPECT_EQ(value.get<double>(), q[field][axis].get<double>()) << field << "." << axis << " seq " << q["header"]["seq"];
      }
    }
    EXPECT_EQ(theirs["landed"], q["landed"]);
  }
  EXPECT_GT(compared, 50) << "states both sides decoded";
  launch.signal(SIGTERM);
  EXPECT_EQ(launch.wait(30s), 0) << launch.output();
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
#endif
}

}  // namespace
