// SPDX-License-Identifier: BSD-3-Clause
// Recorder throughput, the publishing and the discarding side: quad_record_bench publishes
// map updates of a given size as fast as reliable flow control lets it, or receives them
// and throws them away, timing the first to the last.
//   quad_record_bench publish BYTES COUNT     (waits for a reader first)
//   quad_record_bench discard COUNT TIMEOUT_S (prints "received N in S s")
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include "quad/common/time.hpp"
#include "quad/dds/participant.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/raw_type.hpp"
#include "quad/dds/topics.hpp"
#include "quad/dds/waker.hpp"

namespace quad::bench {

int publish(std::size_t bytes, int count)
{
  dds::Participant participant(dds::optionsFromEnvironment("record_bench_publisher"));
  dds::Publisher<msg::MapUpdate> publisher(participant, dds::topics::kMapUpdate);
  const std::int64_t deadline = common::steadyTimeNs() + 10 * common::kNanosecondsPerSecond;
  while (publisher.matchedReaders() == 0 && common::steadyTimeNs() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the reader's side of matching
  msg::MapUpdate update;
  update.resolution(0.2);
  // A serialized MapUpdate: 4 encapsulation + 32 header + 24 + 4 length + 16 per change.
  const std::size_t changes = bytes > 64 ? (bytes - 64) / 16 : 0;
  update.changes().resize(changes);
  const auto start = common::steadyTimeNs();
  for (int i = 1; i <= count; ++i) {
    update.update_seq(static_cast<std::uint64_t>(i));
    update.header().stamp_ns(common::wallTimeNs());
    while (!publisher.write(update)) {
      std::this_thread::sleep_for(std::chrono::microseconds(100));  // history full: a reader is behind
    }
  }
  std::printf("published %d in %.3f s\n", count, common::toSeconds(common::steadyTimeNs() - start));
  // Every sample in the reader's history before returning: a recorder stopped then has them all.
  return publisher.waitForAcknowledgments(std::chrono::seconds(120)) ? 0 : 1;
}

int discard(int count, double timeout_s)
{
  dds::Participant participant(dds::optionsFromEnvironment("record_bench_discard"));
  dds::Waker waker;
  dds::RawSubscriber subscriber(participant, dds::topics::kMapUpdate.info, &waker);
  int received = 0;
  std::int64_t first = 0, last = 0;
  const std::int64_t deadline = common::steadyTimeNs() + common::toNanoseconds(timeout_s);
  dds::RawSample sample;
  while (received < count && common::steadyTimeNs() < deadline) {
    while (subscriber.take(sample)) {
      last = common::steadyTimeNs();
      first = received == 0 ? last : first;
      ++received;
    }
    waker.waitUntil(std::min(deadline, common::steadyTimeNs() + 100'000'000));
  }
  std::printf("received %d in %.3f s\n", received, common::toSeconds(last - first));
  return received == count ? 0 : 1;
}

}  // namespace quad::bench

int main(int argc, char** argv)
{
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "publish" && argc == 4) {
    return quad::bench::publish(std::stoul(argv[2]), std::stoi(argv[3]));
  }
  if (mode == "discard" && argc == 4) {
    return quad::bench::discard(std::stoi(argv[2]), std::stod(argv[3]));
  }
  std::fprintf(stderr, "usage: quad_record_bench publish BYTES COUNT | discard COUNT TIMEOUT_S\n");
  return 2;
}
