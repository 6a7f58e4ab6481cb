// SPDX-License-Identifier: BSD-3-Clause
// MatchedPeers: the endpoints matched now, by GUID, told apart by participant.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "quad/dds/endpoint.hpp"

namespace quad::dds {
namespace {

/// A GUID: the participant's 12-byte prefix (all `participant`), then the entity id `entity`.
std::array<std::uint8_t, 16> guid(std::uint8_t participant, std::uint8_t entity)
{
  std::array<std::uint8_t, 16> g{};
  g.fill(participant);
  g[15] = entity;
  return g;
}

ParticipantPrefix prefix(std::uint8_t participant)
{
  ParticipantPrefix p{};
  p.fill(participant);
  return p;
}

TEST(MatchedPeers, KeepsEachMatchedEndpointOnceUntilItGoesAway)
{
  MatchedPeers peers;
  EXPECT_TRUE(peers.participants().empty());
  peers.update(guid(1, 3).data(), +1);
  peers.update(guid(2, 3).data(), +1);
  peers.update(guid(2, 3).data(), +1);  // told twice: one endpoint
  peers.update(guid(2, 4).data(), +1);  // another endpoint of the same participant
  EXPECT_EQ(peers.participants(), (std::vector<ParticipantPrefix>{prefix(1), prefix(2), prefix(2)}));
  peers.update(guid(2, 3).data(), -1);
  peers.update(guid(9, 1).data(), -1);  // never matched: nothing to remove
  EXPECT_EQ(peers.participants(), (std::vector<ParticipantPrefix>{prefix(1), prefix(2)}));
  peers.update(guid(1, 3).data(), -1);
  peers.update(guid(2, 4).data(), -1);
  EXPECT_TRUE(peers.participants().empty());
}

}  // namespace
}  // namespace quad::dds
