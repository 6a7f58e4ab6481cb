// SPDX-License-Identifier: BSD-3-Clause
// Two processes exchanging topics through quad::dds, over each transport, and the reasons
// reported when endpoints cannot match.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "process.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;

/// Each test case has its own DDS domain so parallel tests never see each other.
std::map<std::string, std::string> env(int domain, const std::string& transport)
{
  return {{"QUAD_DOMAIN_ID", std::to_string(domain)}, {"QUAD_TRANSPORT", transport}};
}

void exchangeCommands(int domain, const std::string& transport)
{
  // GIVEN a reader process and a writer process on one domain and transport
  ChildProcess reader({QUAD_DDS_PROBE, "receive-commands", "200", "30000"}, env(domain, transport));
  ASSERT_TRUE(reader.waitForOutput("ready", 10s)) << reader.output();
  ChildProcess writer({QUAD_DDS_PROBE, "send-commands", "200"}, env(domain, transport));
  // WHEN the writer sends 200 reliable commands
  const auto writer_status = writer.wait(40s);
  const auto reader_status = reader.wait(40s);
  // THEN all 200 arrive, in order, and the writer saw them acknowledged
  EXPECT_EQ(writer_status, 0) << writer.output();
  EXPECT_EQ(reader_status, 0) << reader.output();
  EXPECT_NE(reader.output().find("received 200 of 200"), std::string::npos) << reader.output();
}

TEST(DdsExchange, CommandsCrossProcessesOverUdp) { exchangeCommands(110, "udp"); }

TEST(DdsExchange, CommandsCrossProcessesOverSharedMemory) { exchangeCommands(111, "shm"); }

TEST(DdsExchange, CommandsCrossProcessesOverDefaultTransports) { exchangeCommands(112, "default"); }

TEST(DdsExchange, UdpOnlyAndSharedMemoryOnlyParticipantsNeverMeet)
{
  // The transport option really decides the path: with no transport in common, no match.
  ChildProcess reader({QUAD_DDS_PROBE, "receive-commands", "1", "4000"}, env(113, "shm"));
  ASSERT_TRUE(reader.waitForOutput("ready", 10s)) << reader.output();
  ChildProcess writer({QUAD_DDS_PROBE, "send-commands", "1"}, env(113, "udp"));
  EXPECT_EQ(reader.wait(20s), 1) << reader.output();
  EXPECT_NE(reader.output().find("received 0 of 1"), std::string::npos) << reader.output();
}

TEST(DdsExchange, QosMismatchIsReportedWithThePolicy)
{
  // GIVEN a best-effort writer of quad/sim/state, as its contract says
  ChildProcess writer({QUAD_DDS_PROBE, "send-state", "15000"}, env(114, "udp"));
  // WHEN a reader asks for RELIABLE on it
  ChildProcess reader({QUAD_DDS_PROBE, "receive-state-reliable", "10000"}, env(114, "udp"));
  // THEN the reader is told why it never receives: the RELIABILITY policy
  EXPECT_EQ(reader.wait(20s), 0) << reader.output();
  EXPECT_NE(reader.output().find("quad/sim/state: incompatible QoS: requested QoS policy "
                                 "RELIABILITY is incompatible"),
            std::string::npos)
      << reader.output();
}

TEST(DdsExchange, TypeMismatchIsReportedWithBothTypes)
{
  // GIVEN a writer that puts Heartbeats on quad/sim/state
  ChildProcess writer({QUAD_DDS_PROBE, "send-heartbeat-as-state", "15000"}, env(115, "udp"));
  ASSERT_TRUE(writer.waitForOutput("ready", 10s)) << writer.output();
  // WHEN a VehicleState reader joins the topic
  ChildProcess reader({QUAD_DDS_PROBE, "receive-state", "10000"}, env(115, "udp"));
  // THEN it reports the two types instead of waiting silently
  EXPECT_EQ(reader.wait(20s), 0) << reader.output();
  EXPECT_NE(reader.output().find("type mismatch: remote writer"), std::string::npos)
      << reader.output();
  EXPECT_NE(reader.output().find("'quad::msg::Heartbeat' (keyed), local reader has "
                                 "'quad::msg::VehicleState' (keyed)"),
            std::string::npos)
      << reader.output();
}

}  // namespace

namespace {

std::map<std::string, std::string> serverEnv(int domain, int port)
{
  auto e = env(domain, "udp");
  e["QUAD_DISCOVERY_SERVER"] = "127.0.0.1:" + std::to_string(port);
  return e;
}

TEST(DdsExchange, ClientsMeetThroughADiscoveryServer)
{
  // GIVEN a Fast DDS discovery server and two clients of it (no multicast discovery)
  ChildProcess server({QUAD_FASTDDS_TOOL, "discovery", "-i", "0", "-l", "127.0.0.1", "-p", "11916"});
  ASSERT_TRUE(server.waitForOutput("Server is running", 10s)) << server.output();
  ChildProcess reader({QUAD_DDS_PROBE, "receive-commands", "50", "30000"}, serverEnv(116, 11916));
  ASSERT_TRUE(reader.waitForOutput("ready", 10s)) << reader.output();
  ChildProcess writer({QUAD_DDS_PROBE, "send-commands", "50"}, serverEnv(116, 11916));
  // THEN the commands arrive
  EXPECT_EQ(writer.wait(40s), 0) << writer.output();
  EXPECT_EQ(reader.wait(40s), 0) << reader.output();
  EXPECT_NE(reader.output().find("received 50 of 50"), std::string::npos) << reader.output();
}

TEST(DdsExchange, ClientsOfAnAbsentDiscoveryServerDoNotMeet)
{
  // The same clients without their server: they really rely on it, not on multicast.
  ChildProcess reader({QUAD_DDS_PROBE, "receive-commands", "1", "4000"}, serverEnv(117, 11917));
  ASSERT_TRUE(reader.waitForOutput("ready", 10s)) << reader.output();
  ChildProcess writer({QUAD_DDS_PROBE, "send-commands", "1"}, serverEnv(117, 11917));
  EXPECT_EQ(reader.wait(20s), 1) << reader.output();
  EXPECT_NE(reader.output().find("received 0 of 1"), std::string::npos) << reader.output();
}

}  // namespace
