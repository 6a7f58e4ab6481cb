// SPDX-License-Identifier: BSD-3-Clause
// The MCAP writer alone, against MCAP's own benchmark reference (about 410k messages/s of
// 100 B, 41 MB/s, chunked, on a 2-core NUC): messages written to a file in /tmp, chunked
// and indexed, with and without zstd, and the same bytes fwrite'n as they come (the floor).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <vector>

#include "quad/bag/audit.hpp"
#include "quad/bag/mcap.hpp"

namespace {

const std::filesystem::path kFile = std::filesystem::temp_directory_path() / "quad_mcap_bench.mcap";

void writeMessages(benchmark::State& state, const std::string& compression)
{
  const auto size = static_cast<std::size_t>(state.range(0));
  std::vector<std::uint8_t> payload(size);
  for (std::size_t i = 0; i < size; ++i) {
    payload[i] = static_cast<std::uint8_t>(i * 7);
  }
  quad::bag::McapWriter writer(kFile, 1 << 20, compression);
  const auto channel = writer.addChannel(writer.addSchema("quad::msg::Thing", "omgidl", "struct Thing {};"),
                                         "quad/bench", "cdr", {});
  std::uint64_t t = 1;
  for (auto _ : state) {
    writer.write(channel, static_cast<std::uint32_t>(t), t, t, payload.data(), payload.size());
    ++t;
  }
  writer.close();
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(size));
}

void BM_McapWrite(benchmark::State& state) { writeMessages(state, ""); }
void BM_McapWriteZstd(benchmark::State& state) { writeMessages(state, "zstd"); }

/// The floor: the payload bytes alone, to the same kind of file.
void BM_RawFwrite(benchmark::State& state)
{
  const auto size = static_cast<std::size_t>(state.range(0));
  std::vector<std::uint8_t> payload(size, 1);
  std::FILE* f = std::fopen(kFile.c_str(), "wb");
  for (auto _ : state) {
    std::fwrite(payload.data(), 1, size, f);
  }
  std::fclose(f);
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(size));
}

// The CRC every chunk carries, over a 1 MiB chunk: as crc32 computes it (folded by
// carry-less multiplication on this CPU), and through the tables alone.
template <std::uint32_t (*Crc)(const void*, std::size_t, std::uint32_t)>
void BM_Crc32(benchmark::State& state)
{
  const std::vector<std::uint8_t> data(static_cast<std::size_t>(state.range(0)), 0x5a);
  std::uint32_t crc = 0;
  for (auto _ : state) {
    crc = Crc(data.data(), data.size(), crc);
    benchmark::DoNotOptimize(crc);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}

/// The recorder's loss audit per sample.
void BM_SequenceAudit(benchmark::State& state)
{
  quad::bag::SequenceAudit audit;
  std::uint64_t seq = 1;
  for (auto _ : state) {
    audit.add(42, 0, seq++);
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK(BM_McapWrite)->Arg(100)->Arg(1 << 20);
BENCHMARK(BM_McapWriteZstd)->Arg(100)->Arg(1 << 20);
BENCHMARK(BM_RawFwrite)->Arg(100)->Arg(1 << 20);
BENCHMARK_TEMPLATE(BM_Crc32, quad::bag::crc32)->Arg(1 << 20);
BENCHMARK_TEMPLATE(BM_Crc32, quad::bag::crc32Tables)->Arg(1 << 20);
BENCHMARK(BM_SequenceAudit);

}  // namespace

BENCHMARK_MAIN();
