// SPDX-License-Identifier: BSD-3-Clause
// What the validating transport adds to each received datagram: checkRtpsDatagram on the
// datagrams quad's traffic is made of, side by side with copying the same bytes once (what
// the UDP receive path already does with every datagram).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "quad/wire/rtps_check.hpp"
#include "rtps_builder.hpp"

namespace {

using Bytes = std::vector<std::uint8_t>;

/// INFO_TS + one DATA of `payload` bytes of user CDR (what a state or a cloud fragment is).
Bytes userData(std::size_t payload)
{
  quad::test::RtpsBuilder b(7);
  b.begin(0x09, 0);  // INFO_TS
  b.u32(1);
  b.u32(2);
  b.end();
  b.begin(0x15, 0x04);  // DATA, D
  b.dataHeader(0x00000102, 42, 16, 0x00000107);
  b.u8(0x00);
  b.u8(0x01);  // CDR_LE
  b.u16(0);
  b.fill(payload, 0x5a);
  b.end();
  return b.bytes();
}

/// A DATA with a PL_CDR_LE discovery payload of `parameters` 24-byte locators and a name.
Bytes discoveryData(int parameters)
{
  quad::test::RtpsBuilder b(7);
  b.begin(0x15, 0x04);
  b.dataHeader(0x000100c2, 1, 16, 0x000100c7);
  b.u8(0x00);
  b.u8(0x03);  // PL_CDR_LE
  b.u16(0);
  b.parameter(0x0062, [&] { b.string("quad_plant"); });  // PID_ENTITY_NAME
  for (int i = 0; i < parameters; ++i) {
    b.parameter(0x0031, [&] { b.fill(24, 1); });  // PID_DEFAULT_UNICAST_LOCATOR
  }
  b.sentinel();
  b.end();
  return b.bytes();
}

void run(benchmark::State& state, const Bytes& datagram, bool check)
{
  if (const auto defect = quad::wire::checkRtpsDatagram(datagram.data(), datagram.size())) {
    state.SkipWithError(("the benchmark's datagram is malformed: " + defect->what).c_str());
    return;
  }
  Bytes copy(datagram.size());
  for (auto _ : state) {
    if (check) {
      benchmark::DoNotOptimize(quad::wire::checkRtpsDatagram(datagram.data(), datagram.size()));
    } else {
      std::memcpy(copy.data(), datagram.data(), datagram.size());
      benchmark::DoNotOptimize(copy.data());
      benchmark::ClobberMemory();
    }
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(datagram.size()));
}

void BM_Check_State(benchmark::State& s) { run(s, userData(180), true); }
void BM_Copy_State(benchmark::State& s) { run(s, userData(180), false); }
void BM_Check_Fragment1400(benchmark::State& s) { run(s, userData(1340), true); }
void BM_Copy_Fragment1400(benchmark::State& s) { run(s, userData(1340), false); }
void BM_Check_Datagram64k(benchmark::State& s) { run(s, userData(65000), true); }
void BM_Copy_Datagram64k(benchmark::State& s) { run(s, userData(65000), false); }
void BM_Check_Discovery(benchmark::State& s) { run(s, discoveryData(12), true); }
void BM_Copy_Discovery(benchmark::State& s) { run(s, discoveryData(12), false); }

BENCHMARK(BM_Check_State);
BENCHMARK(BM_Copy_State);
BENCHMARK(BM_Check_Fragment1400);
BENCHMARK(BM_Copy_Fragment1400);
BENCHMARK(BM_Check_Datagram64k);
BENCHMARK(BM_Copy_Datagram64k);
BENCHMARK(BM_Check_Discovery);
BENCHMARK(BM_Copy_Discovery);

}  // namespace

BENCHMARK_MAIN();
