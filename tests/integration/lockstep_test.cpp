// SPDX-License-Identifier: BSD-3-Clause
// Lockstep across processes: the clock owner advances only when every participant is done,
// and names who is late when one is not.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>

#include "process.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;

std::map<std::string, std::string> env(int domain)
{
  return {{"QUAD_DOMAIN_ID", std::to_string(domain)}, {"QUAD_TRANSPORT", "udp"}};
}

TEST(Lockstep, ClockAdvancesStepByStepWithEveryParticipant)
{
  // GIVEN two lockstep participants
  ChildProcess control({QUAD_DDS_PROBE, "lockstep-participant", "control"}, env(120));
  ChildProcess mapping({QUAD_DDS_PROBE, "lockstep-participant", "mapping"}, env(120));
  ASSERT_TRUE(control.waitForOutput("ready", 10s)) << control.output();
  ASSERT_TRUE(mapping.waitForOutput("ready", 10s)) << mapping.output();
  // WHEN the clock owner steps 200 times, waiting for both at each step
  ChildProcess clock({QUAD_DDS_PROBE, "lockstep-clock", "200", "5000", "control", "mapping"},
                     env(120));
  // THEN every step completes
  EXPECT_EQ(clock.wait(60s), 0) << clock.output();
  EXPECT_NE(clock.output().find("stepped 200"), std::string::npos) << clock.output();
}

TEST(Lockstep, TimeoutNamesTheParticipantThatIsLate)
{
  // GIVEN only one of the two expected participants
  ChildProcess control({QUAD_DDS_PROBE, "lockstep-participant", "control"}, env(121));
  ASSERT_TRUE(control.waitForOutput("ready", 10s)) << control.output();
  // WHEN the clock owner waits at most 500 ms for a step
  ChildProcess clock({QUAD_DDS_PROBE, "lockstep-clock", "10", "500", "control", "mapping"},
                     env(121));
  // THEN it gives up naming mapping, and not control
  EXPECT_EQ(clock.wait(30s), 1) << clock.output();
  EXPECT_NE(clock.output().find("lockstep: at sim time 0.001 s, still waiting after 500 ms for: "
                                "mapping (no report yet)\n"),
            std::string::npos)
      << clock.output();
}

}  // namespace
