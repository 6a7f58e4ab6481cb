// SPDX-License-Identifier: BSD-3-Clause
// Participant options from the environment: what every quad process shares with the launcher.
#include "quad/dds/participant.hpp"
#include "quad/dds/topics.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

namespace quad::dds {
namespace {

class EnvironmentOptions : public ::testing::Test {
protected:
  void SetUp() override { clear(); }
  void TearDown() override { clear(); }
  static void clear()
  {
    for (const char* v : {"QUAD_DOMAIN_ID", "QUAD_TRANSPORT", "QUAD_INITIAL_PEERS",
                          "QUAD_DISCOVERY_SERVER", "QUAD_VEHICLE_ID", "QUAD_FAULT_LAYER", "QUAD_UDP_MAX_MESSAGE",
                          "QUAD_INTERFACES", "QUAD_LOCKSTEP", "QUAD_PARTICIPANT_LEASE", "QUAD_MAP_BUDGET_MS",
                          "QUAD_PATH_BUDGET_MS"}) {
      unsetenv(v);
    }
  }
  static std::string errorOf()
  {
    try {
      optionsFromEnvironment("test");
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "accepted";
  }
};

TEST_F(EnvironmentOptions, DefaultsAreDomainZeroAndBuiltinTransports)
{
  const auto o = optionsFromEnvironment("test");
  EXPECT_EQ(o.domain_id, 0);
  EXPECT_EQ(o.transport, Transport::kDefault);
  EXPECT_TRUE(o.initial_peers.empty());
  EXPECT_FALSE(o.qos_file.empty());
  EXPECT_FALSE(o.lockstep);
  EXPECT_EQ(o.participant_lease_s, 0);  // the QoS profile's
  EXPECT_EQ(o.mapBudgetNs(), topics::kMapUpdateBudgetNs);  // the contract's
  EXPECT_EQ(o.pathBudgetNs(), topics::kPathBudgetNs);
}

TEST_F(EnvironmentOptions, ValidValuesAreTaken)
{
  setenv("QUAD_DOMAIN_ID", "42", 1);
  setenv("QUAD_TRANSPORT", "udp", 1);
  setenv("QUAD_INITIAL_PEERS", "10.0.0.1,10.0.0.2:7412", 1);
  setenv("QUAD_DISCOVERY_SERVER", "10.0.0.9:11811", 1);
  setenv("QUAD_VEHICLE_ID", "2", 1);
  setenv("QUAD_FAULT_LAYER", "1", 1);
  setenv("QUAD_UDP_MAX_MESSAGE", "1400", 1);
  setenv("QUAD_INTERFACES", "10.0.0.3,192.168.1.7", 1);
  setenv("QUAD_LOCKSTEP", "1", 1);
  setenv("QUAD_PARTICIPANT_LEASE", "20", 1);
  setenv("QUAD_MAP_BUDGET_MS", "0", 1);
  setenv("QUAD_PATH_BUDGET_MS", "250", 1);
  const auto o = optionsFromEnvironment("test");
  EXPECT_TRUE(o.lockstep);
  EXPECT_EQ(o.participant_lease_s, 20);
  EXPECT_EQ(o.mapBudgetNs(), 0);
  EXPECT_EQ(o.pathBudgetNs(), 250'000'000);
  EXPECT_EQ(o.interfaces, (std::vector<std::string>{"10.0.0.3", "192.168.1.7"}));
  EXPECT_TRUE(o.fault_layer);
  EXPECT_EQ(o.udp_max_message, 1400U);
  EXPECT_EQ(o.domain_id, 42);
  EXPECT_EQ(o.transport, Transport::kUdp);
  EXPECT_EQ(o.initial_peers, (std::vector<std::string>{"10.0.0.1", "10.0.0.2:7412"}));
  EXPECT_EQ(o.discovery_server, "10.0.0.9:11811");
  EXPECT_EQ(o.vehicle_id, 2U);
}

TEST_F(EnvironmentOptions, BadValuesNameTheVariableAndTheValue)
{
  setenv("QUAD_DOMAIN_ID", "abc", 1);
  EXPECT_EQ(errorOf(), "QUAD_DOMAIN_ID: abc: expected an integer in [0, 232]");
  clear();
  setenv("QUAD_FAULT_LAYER", "yes", 1);
  EXPECT_EQ(errorOf(), "QUAD_FAULT_LAYER: yes: expected an integer in [0, 1]");
  clear();
  setenv("QUAD_LOCKSTEP", "2", 1);
  EXPECT_EQ(errorOf(), "QUAD_LOCKSTEP: 2: expected an integer in [0, 1]");
  clear();
  setenv("QUAD_PARTICIPANT_LEASE", "0.5", 1);
  EXPECT_EQ(errorOf(), "QUAD_PARTICIPANT_LEASE: 0.5: expected an integer in [1, 2147483647]");
  clear();
  setenv("QUAD_MAP_BUDGET_MS", "1001", 1);
  EXPECT_EQ(errorOf(), "QUAD_MAP_BUDGET_MS: 1001: expected an integer in [0, 1000]");
  clear();
  setenv("QUAD_PATH_BUDGET_MS", "-1", 1);
  EXPECT_EQ(errorOf(), "QUAD_PATH_BUDGET_MS: -1: expected an integer in [0, 1000]");
  clear();
  setenv("QUAD_UDP_MAX_MESSAGE", "100", 1);
  EXPECT_EQ(errorOf(), "QUAD_UDP_MAX_MESSAGE: 100: expected an integer in [1200, 65500]");
  clear();
  setenv("QUAD_DOMAIN_ID", "233", 1);
  EXPECT_EQ(errorOf(), "QUAD_DOMAIN_ID: 233: expected an integer in [0, 232]");
  clear();
  setenv("QUAD_TRANSPORT", "tcp", 1);
  EXPECT_EQ(errorOf(), "QUAD_TRANSPORT: tcp: expected default, udp or shm");
  clear();
  setenv("QUAD_INITIAL_PEERS", "10.0.0.1,10.0.0", 1);
  EXPECT_EQ(errorOf(), "QUAD_INITIAL_PEERS: 10.0.0: not an IPv4 address");
  clear();
  setenv("QUAD_DISCOVERY_SERVER", "10.0.0.9", 1);
  EXPECT_EQ(errorOf(), "QUAD_DISCOVERY_SERVER: 10.0.0.9: expected IP:PORT");
  setenv("QUAD_DISCOVERY_SERVER", "10.0.0.9:99999", 1);
  EXPECT_EQ(errorOf(), "QUAD_DISCOVERY_SERVER: 99999: expected an integer in [1, 65535]");
  clear();
  setenv("QUAD_INTERFACES", "10.0.0.3,eth0", 1);
  EXPECT_EQ(errorOf(), "QUAD_INTERFACES: eth0: not an IPv4 address");
  setenv("QUAD_INTERFACES", "10.0.0.3:7400", 1);
  EXPECT_EQ(errorOf(), "QUAD_INTERFACES: 10.0.0.3:7400: expected an IPv4 address, without a port");
}

TEST_F(EnvironmentOptions, MissingQosFileIsRefusedNamingIt)
{
  try {
    Participant p(ParticipantOptions{.name = "t", .domain_id = 155, .qos_file = "/nope/qos.xml"});
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "QoS profiles file /nope/qos.xml does not exist");
  }
}

TEST(ParticipantOptions, ADatagramSizeNeedsTheUdpTransport)
{
  ParticipantOptions o{.name = "options_test", .domain_id = 150, .udp_max_message = 1400};
  try {
    Participant p(o);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "participant 'options_test': a UDP datagram size of 1400 bytes needs the udp transport");
  }
}

}  // namespace
}  // namespace quad::dds
