// SPDX-License-Identifier: BSD-3-Clause
// The run's firewall: the domain's DDS ports admit the manifest's hosts and loopback only,
// in a chain of the run's own that removal takes away whole.
#include <gtest/gtest.h>

#include "argv_text.hpp"
#include "quad/launch/firewall.hpp"

namespace quad::launch {
namespace {


using test::joined;

TEST(Firewall, TheDomainsPortsFollowTheRtpsDefaultMapping)
{
  EXPECT_EQ(ddsPorts(0).first, 7400);
  EXPECT_EQ(ddsPorts(0).last, 7649);
  EXPECT_EQ(ddsPorts(181).first, 7400 + 250 * 181);
  EXPECT_EQ(ddsPorts(232).first, 65400);
  EXPECT_EQ(ddsPorts(232).last, 65535);  // ports are 16 bits

}

TEST(Firewall, AdmitsTheNamedAddressesAndLoopbackAndDropsTheRestOfTheDomainsTraffic)
{
  const FirewallRules r = firewallRules("QUAD-1a2b", ddsPorts(1), {11811}, {"10.77.0.1", "10.77.0.2"});
  ASSERT_EQ(r.install.size(), 6U);
  EXPECT_EQ(joined(r.install[0]), "iptables -N QUAD-1a2b");
  EXPECT_EQ(joined(r.install[1]), "iptables -A QUAD-1a2b -i lo -j RETURN");
  EXPECT_EQ(joined(r.install[2]), "iptables -A QUAD-1a2b -s 10.77.0.1 -j RETURN");
  EXPECT_EQ(joined(r.install[3]), "iptables -A QUAD-1a2b -s 10.77.0.2 -j RETURN");
  EXPECT_EQ(joined(r.install[4]),
            "iptables -A QUAD-1a2b -m comment --comment quad launch: DDS from the manifest's hosts only -j DROP");
  // The jump comes last, once the chain is complete: no moment drops a manifest host.
  EXPECT_EQ(joined(r.install[5]), "iptables -I INPUT -p udp -m multiport --dports 7650:7899,11811 -j QUAD-1a2b");
  ASSERT_EQ(r.remove.size(), 3U);
  EXPECT_EQ(joined(r.remove[0]), "iptables -D INPUT -p udp -m multiport --dports 7650:7899,11811 -j QUAD-1a2b");
  EXPECT_EQ(joined(r.remove[1]), "iptables -F QUAD-1a2b");
  EXPECT_EQ(joined(r.remove[2]), "iptables -X QUAD-1a2b");
}

}  // namespace
}  // namespace quad::launch
