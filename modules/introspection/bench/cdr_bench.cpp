// SPDX-License-Identifier: BSD-3-Clause
// Schema-driven decoding (what quad topic echo and the recorder's tools use) against the
// generated Fast CDR deserialization of the same payload, side by side.
#include <benchmark/benchmark.h>

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>

#include <quad/msg/MapUpdatePubSubTypes.h>
#include <quad/msg/PointCloudPubSubTypes.h>
#include <quad/msg/VehicleStatePubSubTypes.h>

#include "quad/introspection/cdr.hpp"

namespace {

template <class Message>
std::vector<char> serialize(Message& m)
{
  std::vector<char> buffer(Message::getMaxCdrSerializedSize() + 4);
  eprosima::fastcdr::FastBuffer fb(buffer.data(), buffer.size());
  eprosima::fastcdr::Cdr cdr(fb, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN,
                             eprosima::fastcdr::Cdr::DDS_CDR);
  cdr.serialize_encapsulation();
  m.serialize(cdr);
  buffer.resize(cdr.getSerializedDataLength());
  return buffer;
}

quad::msg::PointCloud cloud(int points)
{
  quad::msg::PointCloud c;
  c.frame_id("depth_front");
  c.points().resize(static_cast<std::size_t>(points));
  return c;
}

template <class Message>
void generated(benchmark::State& state, Message m)
{
  auto bytes = serialize(m);
  for (auto _ : state) {
    eprosima::fastcdr::FastBuffer fb(bytes.data(), bytes.size());
    eprosima::fastcdr::Cdr cdr(fb, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN,
                               eprosima::fastcdr::Cdr::DDS_CDR);
    cdr.read_encapsulation();
    Message out;
    out.deserialize(cdr);
    benchmark::DoNotOptimize(out);
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(bytes.size()));
}

template <class Message>
void schemaDriven(benchmark::State& state, Message m, const char* type)
{
  auto bytes = serialize(m);
  const std::span<const std::uint8_t> payload(reinterpret_cast<const std::uint8_t*>(bytes.data()),
                                              bytes.size());
  const auto& schema = quad::introspection::quadSchema();
  for (auto _ : state) {
    auto json = quad::introspection::decodeCdr(schema, type, payload);
    benchmark::DoNotOptimize(json);
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(bytes.size()));
}

void BM_VehicleState_Generated(benchmark::State& s) { generated(s, quad::msg::VehicleState{}); }
void BM_VehicleState_SchemaDriven(benchmark::State& s)
{
  schemaDriven(s, quad::msg::VehicleState{}, "quad::msg::VehicleState");
}
void BM_PointCloud1000_Generated(benchmark::State& s) { generated(s, cloud(1000)); }
void BM_PointCloud1000_SchemaDriven(benchmark::State& s)
{
  schemaDriven(s, cloud(1000), "quad::msg::PointCloud");
}

// A reader's check of every sample against its IDL: the types looked up for each payload
// (checkBounds) against once for all (a BoundsChecker kept), side by side.
quad::msg::MapUpdate mapUpdate(int changes)
{
  quad::msg::MapUpdate u;
  u.changes().resize(static_cast<std::size_t>(changes));
  return u;
}

template <class Message>
void boundsEachCall(benchmark::State& state, Message m, const char* type)
{
  auto bytes = serialize(m);
  const std::span<const std::uint8_t> payload(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  for (auto _ : state) {
    benchmark::DoNotOptimize(quad::introspection::checkBounds(quad::introspection::quadSchema(), type, payload));
  }
}

template <class Message>
void boundsChecker(benchmark::State& state, Message m, const char* type)
{
  auto bytes = serialize(m);
  const std::span<const std::uint8_t> payload(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  const quad::introspection::BoundsChecker checker(quad::introspection::quadSchema(), type);
  for (auto _ : state) {
    benchmark::DoNotOptimize(checker.check(payload));
  }
}

void BM_Bounds_VehicleState_EachCall(benchmark::State& s)
{
  boundsEachCall(s, quad::msg::VehicleState{}, "quad::msg::VehicleState");
}
void BM_Bounds_VehicleState_Checker(benchmark::State& s)
{
  boundsChecker(s, quad::msg::VehicleState{}, "quad::msg::VehicleState");
}
void BM_Bounds_MapUpdate5000_EachCall(benchmark::State& s)
{
  boundsEachCall(s, mapUpdate(5000), "quad::msg::MapUpdate");
}
void BM_Bounds_MapUpdate5000_Checker(benchmark::State& s)
{
  boundsChecker(s, mapUpdate(5000), "quad::msg::MapUpdate");
}

BENCHMARK(BM_VehicleState_Generated);
BENCHMARK(BM_VehicleState_SchemaDriven);
BENCHMARK(BM_PointCloud1000_Generated);
BENCHMARK(BM_PointCloud1000_SchemaDriven);
BENCHMARK(BM_Bounds_VehicleState_EachCall);
BENCHMARK(BM_Bounds_VehicleState_Checker);
BENCHMARK(BM_Bounds_MapUpdate5000_EachCall);
BENCHMARK(BM_Bounds_MapUpdate5000_Checker);

}  // namespace

BENCHMARK_MAIN();
