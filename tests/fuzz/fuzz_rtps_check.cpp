// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target: what the validating transport does with every received UDP datagram: the
// RTPS structure check, then, for a datagram it passes, the sequence numbers and counts read
// from it, the sequence guard judging its GAPs and the count guard lowering counts that leap.
// Whatever the bytes, it reads inside them and returns. Corpus: tests/fixtures/datagrams.
#include "harness.hpp"
#include "quad/wire/count_guard.hpp"
#include "quad/wire/rtps_check.hpp"
#include "quad/wire/sequence_guard.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  // The datagram in a buffer of exactly its size, so that a read past it is caught.
  std::vector<std::uint8_t> datagram(data, data + size);
  std::vector<quad::wire::RtpsCount> counts;
  std::vector<quad::wire::RtpsSequence> sequences;
  if (quad::wire::checkRtpsDatagram(datagram.data(), datagram.size(), &counts, &sequences)) {
    return 0;
  }
  // One guard of each across inputs, as one participant keeps them across datagrams.
  static quad::wire::SequenceGuard sequence_guard;
  static quad::wire::CountGuard guard;
  static std::int64_t now_ns = 0;
  now_ns += 1'000'000;
  if (sequence_guard.admit(sequences, now_ns)) {
    return 0;
  }
  const auto tamings = guard.admit(counts, now_ns);
  quad::wire::CountGuard::apply(tamings, datagram.data());
  return 0;
}

std::vector<std::string> quad::fuzz::seeds() { return {}; }
