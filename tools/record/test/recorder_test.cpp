// SPDX-License-Identifier: BSD-3-Clause
// The recorder as a library, against a publisher in another participant: what it writes to
// the file, read back with the MCAP reader. Domain 231.
#include "quad/record/recorder.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "quad/bag/audit.hpp"
#include "quad/bag/mcap.hpp"
#include "quad/dds/participant.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/topics.hpp"
#include "scratch.hpp"
#include "wait.hpp"

namespace quad::record {
namespace {

constexpr int kDomain = 231;  // this test's own
constexpr std::uint32_t kCommands = 30;

TEST(Recorder, EverySampleOfANamedTopicIsWrittenWithItsSchemaInOrderAndItsLossFigures)
{
  dds::intraprocessDeliveryOff();  // two participants in one process (participant.hpp)
  const auto dir = test::scratchDir("quad_recorder_test");
  // GIVEN the recorder running on its own thread for quad/system/command
  RecordOptions options;
  options.connection.domain_id = kDomain;
  options.output = (dir / "commands.mcap").string();
  options.topics = {std::string(dds::topics::kVehicleCommand.info.name)};
  options.quiet = true;
  std::atomic<int> stop{0};
  int code = -1;
  std::thread recorder([&] { code = record(options, stop); });

  // WHEN a writer in another participant sends 30 commands, every one acknowledged
  dds::Participant talker(dds::ParticipantOptions{.name = "talker", .domain_id = kDomain,
                                                  .transport = dds::Transport::kUdp});
  dds::Publisher<msg::VehicleCommand> commands(talker, dds::topics::kVehicleCommand);
  const bool matched = test::waitFor([&] { return commands.matchedReaders() == 1; });
  for (std::uint32_t i = 1; matched && i <= kCommands; ++i) {
    msg::VehicleCommand c;
    c.command_id(i);
    c.kind(msg::COMMAND_HOLD);
    EXPECT_TRUE(commands.write(c));
  }
  const bool acknowledged = matched && commands.waitForAcknowledgments(std::chrono::seconds(10));
  stop.store(1);
  recorder.join();
  ASSERT_TRUE(matched);
  ASSERT_TRUE(acknowledged);
  ASSERT_EQ(code, 0);

  // THEN the file holds the topic's channel (cdr) with the type's IDL (omgidl) and every
  // command in the order sent, and its loss figures say none was missed
  const bag::McapContents file = bag::readMcap(options.output);
  EXPECT_TRUE(file.complete);
  ASSERT_EQ(file.channels.size(), 1U);
  const bag::Channel& channel = file.channels.front();
  EXPECT_EQ(channel.topic, "quad/system/command");
  EXPECT_EQ(channel.message_encoding, "cdr");
  ASSERT_EQ(file.schemas.size(), 1U);
  EXPECT_EQ(file.schemas.front().name, "quad::msg::VehicleCommand");
  EXPECT_EQ(file.schemas.front().encoding, "omgidl");
  ASSERT_EQ(file.messages.size(), kCommands);
  for (std::uint32_t i = 0; i < kCommands; ++i) {
    EXPECT_EQ(file.messages[i].channel_id, channel.id);
    EXPECT_EQ(file.messages[i].sequence, i + 1);  // the header's per-writer number
  }
  const auto loss = bag::parseLossFigures(bag::metadataValues(file, bag::kLossMetadata).at(channel.topic));
  ASSERT_TRUE(loss.has_value());
  EXPECT_EQ(loss->received, kCommands);
  EXPECT_EQ(loss->missing, 0U);
  EXPECT_EQ(loss->duplicated, 0U);
  EXPECT_EQ(loss->reordered, 0U);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace quad::record
