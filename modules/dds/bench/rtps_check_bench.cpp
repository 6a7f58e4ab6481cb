// What the validating transport adds to each received datagram: checkRtpsDatagram on the
// datagrams quad's traffic is made of, side by side with copying the same bytes once (what
// the UDP receive path already does with every datagram).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "quad/dds/rtps_check.hpp"

namespace {

using Bytes = std::vector<std::uint8_t>;

void put16(Bytes& b, std::uint16_t v)
{
  b.push_back(static_cast<std::uint8_t>(v));
  b.push_back(static_cast<std::uint8_t>(v >> 8));
}

void put32(Bytes& b, std::uint32_t v)
{
  put16(b, static_cast<std::uint16_t>(v));
  put16(b, static_cast<std::uint16_t>(v >> 16));
}

Bytes header()
{
  Bytes b = {'R', 'T', 'P', 'S', 2, 3, 0x01, 0x0f};
  b.resize(20, 7);
  return b;
}

/// INFO_TS + one DATA of `payload` bytes of user CDR (what a state or a cloud fragment is).
Bytes userData(std::size_t payload)
{
  Bytes b = header();
  b.push_back(0x09);
  b.push_back(0x01);
  put16(b, 8);
  put32(b, 1);
  put32(b, 2);
  b.push_back(0x15);
  b.push_back(0x05);  // E, D
  put16(b, static_cast<std::uint16_t>(20 + 4 + payload));
  put16(b, 0);
  put16(b, 16);
  put32(b, 0x00000107);
  put32(b, 0x00000102);
  put32(b, 0);
  put32(b, 42);
  b.push_back(0x00);
  b.push_back(0x01);  // CDR_LE
  put16(b, 0);
  b.resize(b.size() + payload, 0x5a);
  return b;
}

/// A DATA with a PL_CDR_LE discovery payload of `parameters` 24-byte locators and a name.
Bytes discoveryData(int parameters)
{
  Bytes b = header();
  b.push_back(0x15);
  b.push_back(0x05);
  const std::size_t length_at = b.size();
  put16(b, 0);
  put16(b, 0);
  put16(b, 16);
  const Bytes entities = {0x00, 0x01, 0x00, 0xc7, 0x00, 0x01, 0x00, 0xc2};  // reader, writer: big-endian
  b.insert(b.end(), entities.begin(), entities.end());
  put32(b, 0);
  put32(b, 1);
  b.push_back(0x00);
  b.push_back(0x03);  // PL_CDR_LE
  put16(b, 0);
  put16(b, 0x0062);  // PID_ENTITY_NAME
  put16(b, 16);
  put32(b, 11);
  for (char c : std::string("quad_plant\0\0", 12)) {
    b.push_back(static_cast<std::uint8_t>(c));
  }
  for (int i = 0; i < parameters; ++i) {
    put16(b, 0x0031);  // PID_DEFAULT_UNICAST_LOCATOR
    put16(b, 24);
    b.resize(b.size() + 24, 1);
  }
  put16(b, 0x0001);
  put16(b, 0);
  const auto length = static_cast<std::uint16_t>(b.size() - length_at - 2);
  b[length_at] = static_cast<std::uint8_t>(length);
  b[length_at + 1] = static_cast<std::uint8_t>(length >> 8);
  return b;
}

void run(benchmark::State& state, const Bytes& datagram, bool check)
{
  if (const auto defect = quad::dds::checkRtpsDatagram(datagram.data(), datagram.size())) {
    state.SkipWithError(("the benchmark's datagram is malformed: " + defect->what).c_str());
    return;
  }
  Bytes copy(datagram.size());
  for (auto _ : state) {
    if (check) {
      benchmark::DoNotOptimize(quad::dds::checkRtpsDatagram(datagram.data(), datagram.size()));
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
