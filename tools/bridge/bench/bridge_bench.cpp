// SPDX-License-Identifier: BSD-3-Clause
// The two DDS ends of quad bridge's benchmark (bridge_bench.sh drives them):
//   quad_bridge_bench publish RATE SECONDS   vehicle states on quad/sim/state at RATE Hz,
//                                            each stamped with its publish time (Header)
//   quad_bridge_bench listen SECONDS         a plain DDS subscriber of the same topic: for
//                                            each sample, receive time minus publish time
// listen prints "count N median_us M p99_us P max_us X".
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "quad/common/time.hpp"
#include "quad/dds/participant.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/dds/waker.hpp"

namespace quad::bench {

int publish(double rate_hz, double seconds)
{
  dds::Participant participant(dds::optionsFromEnvironment("bridge_bench_publisher"));
  dds::Publisher<msg::VehicleState> publisher(participant, dds::topics::kSimState);
  std::this_thread::sleep_for(std::chrono::seconds(2));  // the readers match
  msg::VehicleState state;
  const auto period = static_cast<std::int64_t>(1e9 / rate_hz);
  const std::int64_t start = common::steadyTimeNs();
  const std::int64_t end = start + common::toNanoseconds(seconds);
  std::int64_t next = start;
  int sent = 0;
  while (next < end) {
    std::this_thread::sleep_for(std::chrono::nanoseconds(next - common::steadyTimeNs()));
    state.header().stamp_ns(next - start);
    publisher.write(state);
    ++sent;
    next += period;
  }
  std::printf("published %d\n", sent);
  return 0;
}

int listen(double seconds)
{
  dds::Participant participant(dds::optionsFromEnvironment("bridge_bench_listener"));
  dds::Waker waker;
  dds::Subscriber<msg::VehicleState> subscriber(participant, dds::topics::kSimState, &waker);
  std::vector<double> latency_us;
  const std::int64_t deadline = common::steadyTimeNs() + common::toNanoseconds(seconds);
  while (common::steadyTimeNs() < deadline) {
    while (auto s = subscriber.take()) {
      latency_us.push_back(static_cast<double>(common::wallTimeNs() - s->header().publish_ns()) * 1e-3);
    }
    waker.waitUntil(std::min(deadline, common::steadyTimeNs() + 100'000'000));
  }
  if (latency_us.empty()) {
    std::printf("count 0\n");
    return 1;
  }
  std::sort(latency_us.begin(), latency_us.end());
  const auto at = [&](double q) { return latency_us[static_cast<std::size_t>(q * static_cast<double>(latency_us.size() - 1))]; };
  std::printf("count %zu median_us %.1f p99_us %.1f max_us %.1f\n", latency_us.size(), at(0.5), at(0.99), latency_us.back());
  return 0;
}

}  // namespace quad::bench

int main(int argc, char** argv)
{
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "publish" && argc == 4) {
    return quad::bench::publish(std::stod(argv[2]), std::stod(argv[3]));
  }
  if (mode == "listen" && argc == 3) {
    return quad::bench::listen(std::stod(argv[2]));
  }
  std::fprintf(stderr, "usage: quad_bridge_bench publish RATE SECONDS | listen SECONDS\n");
  return 2;
}
