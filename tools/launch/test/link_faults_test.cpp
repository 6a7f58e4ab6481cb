// SPDX-License-Identifier: BSD-3-Clause
// The commands behind link faults: rules on the host's link only, each undone by its exact
// opposite, and a link taken down comes back with the multicast route DDS discovery needs.
#include <gtest/gtest.h>

#include "argv_text.hpp"
#include "quad/launch/link_faults.hpp"

namespace quad::launch {
namespace {

using Argv = std::vector<std::string>;

using test::joined;

TEST(LinkFaults, LossDropsAtRandomBothWaysOnTheLinkOnlyAndHealsByDeletingTheSameRules)
{
  const LinkFault f{LinkFault::Kind::kLoss, "flight", 0.2, ""};
  const auto c = linkCommands(f, "quad-1-flight", "qv1x2b", "");
  ASSERT_EQ(c.apply.size(), 2U);
  ASSERT_EQ(c.heal.size(), 2U);
  EXPECT_EQ(joined(c.apply[0]),
            "ip netns exec quad-1-flight iptables -A INPUT -i qv1x2b -m statistic --mode random --probability "
            "0.200000 -m comment --comment quad fault -j DROP");
  EXPECT_NE(joined(c.apply[1]).find("quad-1-flight iptables -A OUTPUT -o qv1x2b -m statistic"), std::string::npos);
  for (std::size_t i = 0; i < 2; ++i) {
    Argv undo = c.apply[i];
    undo[5] = "-D";
    EXPECT_EQ(c.heal[i], undo);
  }
  EXPECT_EQ(f.describe(), "loss 0.2 on flight's link");
}

TEST(LinkFaults, APartitionDropsThePeersAddressEitherWay)
{
  const LinkFault f{LinkFault::Kind::kPartition, "flight", 0, "brain"};
  const auto c = linkCommands(f, "ns", "veth", "10.77.0.3");
  ASSERT_EQ(c.apply.size(), 2U);
  EXPECT_NE(joined(c.apply[0]).find("INPUT -i veth -s 10.77.0.3 -m comment"), std::string::npos);
  EXPECT_NE(joined(c.apply[1]).find("OUTPUT -o veth -d 10.77.0.3 -m comment"), std::string::npos);
  EXPECT_EQ(f.describe(), "partition flight | brain");
}

TEST(LinkFaults, ALinkTakenDownComesBackWithItsMulticastRoute)
{
  const LinkFault f{LinkFault::Kind::kDown, "sim", 0, ""};
  const auto c = linkCommands(f, "ns", "veth", "");
  ASSERT_EQ(c.apply.size(), 1U);
  EXPECT_EQ(joined(c.apply[0]), "ip -n ns link set veth down");
  ASSERT_EQ(c.heal.size(), 2U);
  EXPECT_EQ(joined(c.heal[0]), "ip -n ns link set veth up");
  EXPECT_EQ(joined(c.heal[1]), std::string("ip -n ns route replace ") + kMulticastRoute + " dev veth");
}

}  // namespace
}  // namespace quad::launch
