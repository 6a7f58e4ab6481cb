// SPDX-License-Identifier: BSD-3-Clause
#include "quad/introspection/cdr.hpp"

#include <algorithm>

#include <gtest/gtest.h>

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>

#include <foxglove/SceneUpdatePubSubTypes.h>
#include <quad/msg/HeartbeatPubSubTypes.h>
#include <quad/msg/PointCloudPubSubTypes.h>
#include <quad/msg/VehicleStatePubSubTypes.h>

#include <random>
#include <vector>

namespace quad::introspection {
namespace {

/// Serializes a generated message as Fast DDS does: encapsulation header, then CDR.
template <class Message>
std::vector<std::uint8_t> serialize(Message& m, bool big_endian = false)
{
  // The sample's own size: a scene's largest would be hundreds of megabytes.
  std::vector<char> buffer(Message::getCdrSerializedSize(m) + 4);
  eprosima::fastcdr::FastBuffer fb(buffer.data(), buffer.size());
  eprosima::fastcdr::Cdr cdr(fb,
                             big_endian ? eprosima::fastcdr::Cdr::BIG_ENDIANNESS
                                        : eprosima::fastcdr::Cdr::LITTLE_ENDIANNESS,
                             eprosima::fastcdr::Cdr::DDS_CDR);
  cdr.serialize_encapsulation();
  m.serialize(cdr);
  return {buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(cdr.getSerializedDataLength())};
}

msg::VehicleState sampleState()
{
  msg::VehicleState s;
  s.header().vehicle_id(7);
  s.header().stamp_ns(1'234'567'890'123LL);
  s.header().seq(42);
  s.p_W().x(1.5);
  s.p_W().y(-2.25);
  s.p_W().z(3.0);
  s.q_WB().w(0.5);
  s.q_WB().x(-0.5);
  s.w_B().z(0.125);
  s.landed(true);
  return s;
}

TEST(Cdr, DecodesWhatFastCdrSerializedInBothByteOrders)
{
  for (const bool big_endian : {false, true}) {
    msg::VehicleState s = sampleState();
    const auto bytes = serialize(s, big_endian);
    const auto j = decodeCdr(quadSchema(), "quad::msg::VehicleState", bytes);
    EXPECT_EQ(j["header"]["vehicle_id"], 7);
    EXPECT_EQ(j["header"]["stamp_ns"], 1'234'567'890'123LL);
    EXPECT_EQ(j["header"]["seq"], 42);
    EXPECT_EQ(j["p_W"]["y"], -2.25);
    EXPECT_EQ(j["q_WB"]["w"], 0.5);
    EXPECT_EQ(j["q_WB"]["x"], -0.5);
    EXPECT_EQ(j["w_B"]["z"], 0.125);
    EXPECT_EQ(j["landed"], true);
  }
}

TEST(Cdr, DecodesStringsEnumsAndSequences)
{
  msg::Heartbeat hb;
  hb.module_name("mapping");
  hb.host("host-a");
  hb.pid(4242);
  hb.state(msg::MODULE_DEGRADED);
  hb.errors(3);
  auto j = decodeCdr(quadSchema(), "quad::msg::Heartbeat", serialize(hb));
  EXPECT_EQ(j["module_name"], "mapping");
  EXPECT_EQ(j["host"], "host-a");
  EXPECT_EQ(j["pid"], 4242);
  EXPECT_EQ(j["state"], "MODULE_DEGRADED");
  EXPECT_EQ(j["errors"], 3);

  msg::PointCloud cloud;
  cloud.frame_id("depth_front");
  for (int i = 0; i < 10; ++i) {
    msg::Point3f p;
    p.x(static_cast<float>(i));
    cloud.points().push_back(p);
  }
  cloud.max_range(12.5f);
  j = decodeCdr(quadSchema(), "quad::msg::PointCloud", serialize(cloud), {.max_elements = 3});
  EXPECT_EQ(j["frame_id"], "depth_front");
  ASSERT_EQ(j["points"].size(), 4U);  // three points, then the count of the others
  EXPECT_EQ(j["points"][2]["x"], 2.0);
  EXPECT_EQ(j["points"][3], "... 7 more");
  EXPECT_EQ(j["max_range"], 12.5);
}

TEST(Cdr, EveryTruncationIsAnErrorNeverACrash)
{
  msg::Heartbeat hb;
  hb.module_name("control");
  hb.host("h");
  const auto bytes = serialize(hb);
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    EXPECT_THROW(decodeCdr(quadSchema(), "quad::msg::Heartbeat",
                           std::span<const std::uint8_t>(bytes.data(), n)),
                 DecodeError)
        << "prefix of " << n << " bytes";
  }
}

TEST(Cdr, RandomCorruptionIsDecodedOrRefusedNeverACrash)
{
  msg::PointCloud cloud;
  cloud.frame_id("depth_front");
  cloud.points().resize(16);
  const auto clean = serialize(cloud);
  std::mt19937 rng(1234);
  int refused = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    auto bytes = clean;
    for (int k = 0; k < 3; ++k) {
      bytes[4 + rng() % (bytes.size() - 4)] = static_cast<std::uint8_t>(rng());
    }
    try {
      decodeCdr(quadSchema(), "quad::msg::PointCloud", bytes);
    } catch (const DecodeError&) {
      ++refused;
    }
  }
  EXPECT_GT(refused, 0);  // the corruptions did hit lengths, enums and strings
}

TEST(Cdr, BoundsEnumsAndEncapsulationAreChecked)
{
  msg::Heartbeat hb;
  hb.module_name("x");
  auto bytes = serialize(hb);
  // module_name is the first member after the 32-byte Header: its length word at body 32.
  bytes[4 + 32] = 200;  // length 200 > bound 32
  EXPECT_THROW(decodeCdr(quadSchema(), "quad::msg::Heartbeat", bytes), DecodeError);

  msg::VehicleState s = sampleState();
  auto state = serialize(s);
  state[1] = 0x02;  // PL_CDR_BE: not plain CDR
  try {
    decodeCdr(quadSchema(), "quad::msg::VehicleState", state);
    FAIL();
  } catch (const DecodeError& e) {
    EXPECT_NE(std::string(e.what()).find("unsupported encapsulation"), std::string::npos);
  }
  EXPECT_THROW(decodeCdr(quadSchema(), "quad::msg::Nope", state), DecodeError);
}

TEST(Cdr, ErrorsNameTheFieldPath)
{
  msg::VehicleState s = sampleState();
  const auto bytes = serialize(s);
  try {
    decodeCdr(quadSchema(), "quad::msg::VehicleState",
              std::span<const std::uint8_t>(bytes.data(), 4 + 32 + 8));
    FAIL();
  } catch (const DecodeError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("p_W.y: truncated", 0), 0U) << e.what();
  }
}

}  // namespace
}  // namespace quad::introspection

namespace quad::introspection {
namespace {

TEST(CdrEncode, EncodedSamplesDeserializeIntoTheGeneratedType)
{
  // GIVEN a sample described as decodeCdr prints it, with members left out
  const auto value = nlohmann::ordered_json::parse(R"({
    "header": {"vehicle_id": 7, "stamp_ns": 123, "seq": 9},
    "p_W": {"x": 1.5, "y": -2.0},
    "q_WB": {"w": 1.0},
    "landed": true})");
  // WHEN it is encoded and deserialized by the generated code
  auto bytes = encodeCdr(quadSchema(), "quad::msg::VehicleState", value);
  eprosima::fastcdr::FastBuffer fb(reinterpret_cast<char*>(bytes.data()), bytes.size());
  eprosima::fastcdr::Cdr cdr(fb, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN,
                             eprosima::fastcdr::Cdr::DDS_CDR);
  cdr.read_encapsulation();
  msg::VehicleState s;
  s.deserialize(cdr);
  // THEN given members carry their values and the others are zero
  EXPECT_EQ(s.header().vehicle_id(), 7U);
  EXPECT_EQ(s.header().seq(), 9U);
  EXPECT_EQ(s.p_W().x(), 1.5);
  EXPECT_EQ(s.p_W().y(), -2.0);
  EXPECT_EQ(s.p_W().z(), 0.0);
  EXPECT_EQ(s.q_WB().w(), 1.0);
  EXPECT_TRUE(s.landed());
}

TEST(CdrEncode, DecodeOfEncodeIsTheIdentityOnFullSamples)
{
  msg::Heartbeat hb;
  hb.module_name("planning");
  hb.host("h1");
  hb.pid(77);
  hb.state(msg::MODULE_STOPPING);
  const auto decoded = decodeCdr(quadSchema(), "quad::msg::Heartbeat", serialize(hb));
  const auto again = encodeCdr(quadSchema(), "quad::msg::Heartbeat", decoded);
  EXPECT_EQ(again, serialize(hb));
}

TEST(CdrEncode, BadValuesNameTheFieldPath)
{
  const auto error = [](const char* type, const char* json) {
    try {
      encodeCdr(quadSchema(), type, nlohmann::ordered_json::parse(json));
    } catch (const EncodeError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error("quad::msg::Goal", R"({"p_W": {"w": 1}})"),
            "p_W.w: unknown field of quad::msg::Vector3 (fields: x, y, z)");
  EXPECT_EQ(error("quad::msg::Goal", R"({"goal_id": -1})"), "goal_id: -1 is negative");
  EXPECT_EQ(error("quad::msg::Goal", R"({"tolerance": "far"})"),
            "tolerance: expected a number, got \"far\"");
  EXPECT_EQ(error("quad::msg::VehicleCommand", R"({"kind": "COMMAND_FLIP"})"),
            "kind: \"COMMAND_FLIP\" is not one of COMMAND_ARM, COMMAND_DISARM, COMMAND_TAKEOFF, "
            "COMMAND_START_MISSION, COMMAND_HOLD, COMMAND_LAND, COMMAND_SAVE_MAP, COMMAND_RETURN");
  EXPECT_EQ(error("quad::msg::ActuatorCommand", R"({"rotor_speed": [1, 2, 3]})"),
            "rotor_speed: expected a list of 4, got [1,2,3]");
  EXPECT_EQ(error("quad::msg::Heartbeat", R"({"module_name": "a-module-name-longer-than-32-chars"})"),
            "module_name: string of 34 characters exceeds its bound 32");
}

nlohmann::ordered_json pathOf(std::size_t waypoints)
{
  nlohmann::ordered_json p = {{"header", {{"seq", 1}}}, {"waypoints_W", nlohmann::ordered_json::array()}};
  for (std::size_t i = 0; i < waypoints; ++i) {
    p["waypoints_W"].push_back({{"x", static_cast<double>(i)}, {"y", 0.0}, {"z", 2.0}});
  }
  return p;
}

TEST(CdrBounds, SamplesThatKeepToTheirIdlPassAndOversizedOnesAreNamed)
{
  // Within its bound (4096 waypoints), a path passes; the generated code would read the
  // oversized one whole, so the check is what refuses it.
  EXPECT_EQ(checkBounds(quadSchema(), "quad::msg::Path", encodeCdr(quadSchema(), "quad::msg::Path", pathOf(4096))), "");
  EXPECT_THROW(encodeCdr(quadSchema(), "quad::msg::Path", pathOf(4097)), EncodeError);
  const auto oversized = encodeCdr(quadSchema(), "quad::msg::Path", pathOf(5000), {.enforce_bounds = false});
  const std::string why = checkBounds(quadSchema(), "quad::msg::Path", oversized);
  EXPECT_EQ(why.rfind("waypoints_W: sequence length 5000 exceeds its bound 4096 at byte ", 0), 0U) << why;
  // Whatever decodeCdr refuses, checkBounds refuses too.
  EXPECT_THROW(decodeCdr(quadSchema(), "quad::msg::Path", oversized), DecodeError);
}

TEST(CdrBounds, ABooleanByteOtherThanZeroOrOneIsRefused)
{
  // Found by fuzz_idl_types: Fast CDR throws on such a byte from a reader's thread, which
  // ends the process; the check refuses the payload first.
  const nlohmann::ordered_json armed = {{"armed", true}};
  auto bytes = encodeCdr(quadSchema(), "quad::msg::ActuatorCommand", armed);
  ASSERT_EQ(checkBounds(quadSchema(), "quad::msg::ActuatorCommand", bytes), "");
  // Every other member is zero: the last byte that is 1 is `armed`.
  const auto at = std::find(bytes.rbegin(), bytes.rend(), std::uint8_t{1});
  ASSERT_NE(at, bytes.rend());
  *at = 2;
  const std::string why = checkBounds(quadSchema(), "quad::msg::ActuatorCommand", bytes);
  EXPECT_EQ(why.rfind("armed: boolean value 2 is neither 0 nor 1 at byte ", 0), 0U) << why;
}

TEST(CdrBounds, TruncatedPayloadsLongStringsAndBadEnumsAreRefused)
{
  msg::Heartbeat hb;
  hb.module_name("planning");
  hb.pid(3);
  auto bytes = serialize(hb);
  EXPECT_EQ(checkBounds(quadSchema(), "quad::msg::Heartbeat", bytes), "");
  auto cut = bytes;
  cut.resize(cut.size() - 6);
  EXPECT_NE(checkBounds(quadSchema(), "quad::msg::Heartbeat", cut).find("truncated"), std::string::npos);
  const auto long_name = encodeCdr(quadSchema(), "quad::msg::Heartbeat",
                                   {{"module_name", std::string(40, 'm')}}, {.enforce_bounds = false});
  EXPECT_NE(checkBounds(quadSchema(), "quad::msg::Heartbeat", long_name)
                .find("module_name: string length 40 exceeds its bound 32"),
            std::string::npos);
  // Two statuses that differ in their mode only show where the mode's bytes are.
  const nlohmann::ordered_json first = {{"mode", "CONTROL_DISARMED"}};
  const nlohmann::ordered_json last = {{"mode", "CONTROL_FAILSAFE_LAND"}};
  auto a = encodeCdr(quadSchema(), "quad::msg::ControlStatus", first);
  auto b = encodeCdr(quadSchema(), "quad::msg::ControlStatus", last);
  ASSERT_EQ(a.size(), b.size());
  std::size_t at = 0;
  while (at < a.size() && a[at] == b[at]) {
    ++at;
  }
  ASSERT_LT(at, a.size());
  b[at] = 99;
  EXPECT_NE(checkBounds(quadSchema(), "quad::msg::ControlStatus", b).find("enum value 99 is not an enumerator"),
            std::string::npos);
  EXPECT_EQ(checkBounds(quadSchema(), "quad::msg::Nothing", a), "no IDL struct named 'quad::msg::Nothing'");
}

TEST(CdrBounds, RunsOfOneFieldSizeAreSkippedTheirEnumsReadAndAFaultNamedWhereItIs)
{
  // Map changes (3 longs and an enum each) and points (3 floats) are runs of one field size:
  // both must end exactly where the payload does for a sample that keeps to its IDL.
  nlohmann::ordered_json update = {{"changes", nlohmann::ordered_json::array()}};
  for (int i = 0; i < 100; ++i) {
    update["changes"].push_back({{"ix", i}, {"iy", -i}, {"iz", 3}, {"state", "VOXEL_OCCUPIED"}});
  }
  auto changes = encodeCdr(quadSchema(), "quad::msg::MapUpdate", update);
  EXPECT_EQ(checkBounds(quadSchema(), "quad::msg::MapUpdate", changes), "");
  // The run is skipped, not its enums: a state that is no enumerator in change 57 (the
  // payload's 16-byte changes end it) is refused, and named as a walk element by element would.
  const std::size_t state_57 = changes.size() - 16 * (100 - 57) + 12;
  ASSERT_EQ(changes[state_57], 2);  // VOXEL_OCCUPIED
  changes[state_57] = 7;
  const std::string why = checkBounds(quadSchema(), "quad::msg::MapUpdate", changes);
  EXPECT_EQ(why, "changes[57].state: enum value 7 is not an enumerator of quad::msg::VoxelState at byte " +
                     std::to_string(state_57 + 4));
  // A checker kept for every sample answers as checkBounds does.
  const BoundsChecker checker(quadSchema(), "quad::msg::MapUpdate");
  EXPECT_EQ(checker.check(changes), why);
  EXPECT_EQ(quadBoundsChecker("quad::msg::MapUpdate")->check(changes), why);
  EXPECT_EQ(quadBoundsChecker("quad::msg::Nothing"), nullptr);

  nlohmann::ordered_json cloud = {{"points", nlohmann::ordered_json::array()}};
  for (int i = 0; i < 1000; ++i) {
    cloud["points"].push_back({{"x", 1.0}, {"y", 2.0}, {"z", 3.0}});
  }
  auto bytes = encodeCdr(quadSchema(), "quad::msg::PointCloud", cloud);
  EXPECT_EQ(checkBounds(quadSchema(), "quad::msg::PointCloud", bytes), "");
  bytes.resize(bytes.size() - 12);  // one point short of what the length announces
  EXPECT_NE(checkBounds(quadSchema(), "quad::msg::PointCloud", bytes).find("truncated"), std::string::npos);
}

TEST(CdrBounds, AnEmptyRunOfFixedLayoutAddsNoPadding)
{
  // Fast CDR aligns a sequence's element as it writes it, so an empty sequence of doubles'
  // structs is its length alone. Scenes as the display draws them (entities of boxes,
  // cylinders and spheres, any list of them empty) pass, as decodeCdr reads them.
  std::mt19937 rng(11);
  const auto upTo = [&rng](int n) { return std::uniform_int_distribution<int>(0, n)(rng); };
  for (int trial = 0; trial < 60; ++trial) {
    foxglove::SceneUpdate scene;
    for (int e = upTo(3); e >= 0; --e) {
      foxglove::SceneEntity entity;
      entity.frame_id(std::string(static_cast<std::size_t>(upTo(9)), 'w'));
      entity.id(std::string(static_cast<std::size_t>(upTo(9)), 'e'));
      entity.frame_locked(upTo(1) == 1);
      entity.cubes().resize(static_cast<std::size_t>(upTo(2)));
      entity.spheres().resize(static_cast<std::size_t>(upTo(2)));
      entity.cylinders().resize(static_cast<std::size_t>(upTo(2)));
      entity.arrows().resize(static_cast<std::size_t>(upTo(1)));
      scene.entities().push_back(entity);
    }
    const auto bytes = serialize(scene);
    ASSERT_NO_THROW(decodeCdr(quadSchema(), "foxglove::SceneUpdate", bytes)) << "trial " << trial;
    ASSERT_EQ(checkBounds(quadSchema(), "foxglove::SceneUpdate", bytes), "") << "trial " << trial;
  }
}

}  // namespace
}  // namespace quad::introspection
