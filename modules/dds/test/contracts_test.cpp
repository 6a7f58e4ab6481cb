// SPDX-License-Identifier: BSD-3-Clause
// The topic contracts against the design's conventions, the IDL, and the QoS file.
#include "quad/dds/topics.hpp"

#include <gtest/gtest.h>

#include <regex>
#include <set>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include "quad/dds/participant.hpp"
#include "quad/dds/raw_type.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/introspection/idl.hpp"

namespace quad::dds {
namespace {

namespace fdds = eprosima::fastdds::dds;

/// Each test that creates a participant uses its own domain.
Participant testParticipant(int domain)
{
  return Participant(ParticipantOptions{.name = "contracts_test", .domain_id = domain,
                                        .transport = Transport::kUdp});
}

double seconds(const eprosima::fastrtps::Duration_t& d)
{
  return d.seconds + d.nanosec * 1e-9;
}

TEST(Contracts, NamesAreUniqueAndFollowTheConvention)
{
  const std::regex pattern("quad/(sim|estimation|mapping|planning|control|system|display)/[a-z_]+");
  std::set<std::string_view> names;
  for (const auto& t : topics::kAll) {
    EXPECT_TRUE(std::regex_match(std::string(t.name), pattern)) << t.name;
    EXPECT_TRUE(names.insert(t.name).second) << "declared twice: " << t.name;
    EXPECT_GE(t.rate_hz, 0.0) << t.name;
    EXPECT_FALSE(t.description.empty()) << t.name;
  }
}

TEST(Contracts, EveryTypeIsAnIdlStructWithItsFile)
{
  const auto& schema = introspection::quadSchema();
  for (const auto& t : topics::kAll) {
    const auto* def = schema.findStruct(t.type_name);
    ASSERT_NE(def, nullptr) << t.name << ": " << t.type_name;
    EXPECT_EQ(def->file, t.idl_file) << t.name;
    // quad's own messages lead with the keyed Header; only the display topics carry
    // Foxglove's schemas, which do not.
    const bool display = t.name.starts_with("quad/display/");
    EXPECT_EQ(t.has_header, !display) << t.name;
    EXPECT_EQ(t.type_name.starts_with("foxglove::"), display) << t.name;
    EXPECT_EQ(t.owner == Owner::kDisplay, display) << t.name;
  }
}

TEST(Contracts, LookupFindsDeclaredTopicsOnly)
{
  ASSERT_TRUE(topics::find("quad/sim/state").has_value());
  EXPECT_EQ(topics::find("quad/sim/state")->type_name, "quad::msg::VehicleState");
  EXPECT_FALSE(topics::find("quad/sim/stat").has_value());
}

TEST(Contracts, GeneratedTypeNamesMatchTheContracts)
{
  EXPECT_EQ(MessageTraits<msg::VehicleState>::PubSubType().getName(),
            topics::kSimState.info.type_name);
  EXPECT_EQ(MessageTraits<msg::Heartbeat>::PubSubType().getName(),
            topics::kHeartbeat.info.type_name);
  EXPECT_EQ(MessageTraits<msg::MapSnapshot>::PubSubType().getName(),
            topics::kMapSnapshot.info.type_name);
}

TEST(Contracts, EveryQosClassHasAWriterAndAReaderProfile)
{
  Participant p = testParticipant(150);
  for (const auto& t : topics::kAll) {
    EXPECT_NO_THROW(p.writerQos(t.qos_profile)) << t.name;
    EXPECT_NO_THROW(p.readerQos(t.qos_profile)) << t.name;
  }
  EXPECT_THROW(p.writerQos("no_such_class"), std::runtime_error);
}

TEST(Contracts, EveryTopicCanHaveAWriterAndAReader)
{
  // Loading a profile is not enough: Fast DDS checks resource limits only when it creates
  // the entity.
  Participant p = testParticipant(156);
  for (const auto& t : topics::kAll) {
    EXPECT_NO_THROW({
      RawPublisher writer(p, t);
      RawSubscriber reader(p, t, nullptr);
    }) << t.name;
  }
}

TEST(Contracts, ParticipantUsesTheBaselineLeaseNotTheTwentySecondDefault)
{
  Participant p = testParticipant(151);
  fdds::DomainParticipantQos qos;
  ASSERT_EQ(p.raw()->get_qos(qos), ReturnCode_t::RETCODE_OK);
  const auto& discovery = qos.wire_protocol().builtin.discovery_config;
  EXPECT_DOUBLE_EQ(seconds(discovery.leaseDuration), 2.0);
  EXPECT_DOUBLE_EQ(seconds(discovery.leaseDuration_announcementperiod), 0.5);
}

TEST(Contracts, ReliableWritersHeartbeatEvery100msAndOnlyTheModulesHeartbeatHasALivelinessLease)
{
  Participant p = testParticipant(152);
  for (const auto& t : topics::kAll) {
    const auto w = p.writerQos(t.qos_profile);
    const auto r = p.readerQos(t.qos_profile);
    if (t.qos_profile == "heartbeat") {
      // a module's life: asserted by its node, lost within half a second of its end
      EXPECT_EQ(w.liveliness().kind, fdds::MANUAL_BY_TOPIC_LIVELINESS_QOS) << t.name;
      EXPECT_DOUBLE_EQ(seconds(w.liveliness().lease_duration), 0.5) << t.name;
      EXPECT_DOUBLE_EQ(seconds(r.liveliness().lease_duration), 0.5) << t.name;
    } else {
      // data: no lease offered or asked (a writer of any vendor's defaults matches)
      EXPECT_EQ(w.liveliness().kind, fdds::AUTOMATIC_LIVELINESS_QOS) << t.name;
      EXPECT_EQ(w.liveliness().lease_duration, eprosima::fastrtps::c_TimeInfinite) << t.name;
      EXPECT_EQ(r.liveliness().lease_duration, eprosima::fastrtps::c_TimeInfinite) << t.name;
    }
    if (w.reliability().kind == fdds::RELIABLE_RELIABILITY_QOS) {
      EXPECT_DOUBLE_EQ(seconds(w.reliable_writer_qos().times.heartbeatPeriod), 0.1) << t.name;
    }
  }
}

TEST(Contracts, ControlInputsHaveDeadlinesOfTwiceTheirPeriod)
{
  Participant p = testParticipant(153);
  for (const auto* t : {&topics::kSimState.info, &topics::kActuators.info}) {
    const double expected = 2.0 / t->rate_hz;
    EXPECT_NEAR(seconds(p.readerQos(t->qos_profile).deadline().period), expected, 1e-9) << t->name;
    EXPECT_NEAR(seconds(p.writerQos(t->qos_profile).deadline().period), expected, 1e-9) << t->name;
  }
}

TEST(Contracts, ATopicsStalenessIsItsReadersDdsDeadlineAndItsWritersOfferIt)
{
  // A reader asks for a sample within the contract's deadline (the middleware's deadline
  // event then reaches the node); a writer offers it, or its class's tighter one, so both
  // match.
  Participant p = testParticipant(155);
  int judged = 0;
  for (const auto& t : topics::kAll) {
    const double reader = seconds(p.readerQos(t).deadline().period);
    const double writer = seconds(p.writerQos(t).deadline().period);
    if (t.stale_after_s > 0.0) {
      ++judged;
      EXPECT_NEAR(reader, t.stale_after_s, 1e-9) << t.name;
      EXPECT_LE(writer, reader) << t.name;
    } else {
      EXPECT_NEAR(reader, seconds(p.readerQos(t.qos_profile).deadline().period), 1e-9) << t.name;
    }
  }
  EXPECT_EQ(judged, 4);  // the true state, the estimated state, the battery, the path
  EXPECT_NEAR(seconds(p.writerQos(topics::kSimState.info).deadline().period), 0.008, 1e-9);  // its class's
}

TEST(Contracts, WritersAndReadersOfOneClassAreCompatible)
{
  // A writer and a reader built from one class must match: same reliability and durability
  // (a reader never asks more than the writer offers).
  Participant p = testParticipant(154);
  for (const auto& t : topics::kAll) {
    const auto w = p.writerQos(t.qos_profile);
    const auto r = p.readerQos(t.qos_profile);
    EXPECT_EQ(w.reliability().kind, r.reliability().kind) << t.name;
    EXPECT_EQ(w.durability().kind, r.durability().kind) << t.name;
  }
}

TEST(Contracts, ARawEndpointTakesTheTypedSupportOfItsParticipantAndATypedOneIsRefusedARawOne)
{
  // Fast DDS would serialise the raw samples with the generated type's code, or the reverse:
  // one type name has one support per participant. A raw endpoint made after a typed one
  // uses the typed support (and converts each sample, raw_take_test.cpp).
  Participant p = testParticipant(158);
  Subscriber<msg::Path> typed(p, topics::kPath);
  EXPECT_EQ(dynamic_cast<const RawType*>(payloadTypeFor(p, topics::kPath.info).get()), nullptr);
  EXPECT_NO_THROW(RawPublisher(p, topics::kPath.info));
  // Another domain: matched with p's reader, q's writer made the test's end a race between
  // the two participants' teardown and a match's callbacks (a crash, once in a CI run).
  Participant q = testParticipant(90);
  RawPublisher raw(q, topics::kPath.info);
  EXPECT_THROW(Subscriber<msg::Path>(q, topics::kPath), std::logic_error);
}

}  // namespace
}  // namespace quad::dds
