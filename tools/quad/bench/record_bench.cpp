// SPDX-License-Identifier: BSD-3-Clause
// Recorder cost and throughput, the publishing and the discarding side: quad_record_bench
// publishes map updates of a given size as fast as reliable flow control lets it, or
// receives them and throws them away, timing the first to the last; and it runs a command
// and reports the CPU time that command's process took (its rusage, as wait4 gives it).
//   quad_record_bench publish BYTES COUNT     (waits for a reader first)
//   quad_record_bench discard COUNT TIMEOUT_S (prints "received N in S s")
//   quad_record_bench cpu FILE -- COMMAND...  (writes its CPU seconds to FILE; SIGINT and
//                                              SIGTERM are passed on to the command)
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

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

namespace {
volatile std::sig_atomic_t g_child = 0;
void passOn(int signal)
{
  if (g_child > 0) {
    ::kill(static_cast<pid_t>(g_child), signal);
  }
}
}  // namespace

/// Runs argv[0...] as a child process and writes the CPU time it took (user plus system, all
/// its threads) to `file`; returns its exit status.
int cpu(const char* file, char** argv)
{
  std::signal(SIGINT, passOn);
  std::signal(SIGTERM, passOn);
  const pid_t child = ::fork();
  if (child < 0) {
    std::perror("fork");
    return 2;
  }
  if (child == 0) {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    ::execvp(argv[0], argv);
    std::perror(argv[0]);
    std::_Exit(127);
  }
  g_child = child;
  int status = 0;
  rusage usage{};
  while (::wait4(child, &status, 0, &usage) < 0) {
    if (errno != EINTR) {
      std::perror("wait4");
      return 2;
    }
  }
  std::FILE* out = std::fopen(file, "w");
  if (out == nullptr) {
    std::perror(file);
    return 2;
  }
  std::fprintf(out, "%.6f\n", common::cpuSeconds(usage));
  std::fclose(out);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
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
  if (mode == "cpu" && argc > 4 && std::string(argv[3]) == "--") {
    return quad::bench::cpu(argv[2], argv + 4);
  }
  std::fprintf(stderr,
               "usage: quad_record_bench publish BYTES COUNT | discard COUNT TIMEOUT_S | cpu FILE -- COMMAND...\n");
  return 2;
}
