// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Time in quad: integer nanoseconds everywhere on the wire and in cores (int64 holds ±292
/// years), seconds as double only inside algorithms. Cores never read a clock: the node
/// passes the time in (sim time from quad/sim/clock, or wall time when no simulation runs).

#include <cmath>
#include <cstdint>

struct rusage;  // <sys/resource.h>

namespace quad::common {

inline constexpr std::int64_t kNanosecondsPerSecond = 1'000'000'000;

/// [ns] CLOCK_REALTIME since the Unix epoch: what Header.publish_ns carries.
std::int64_t wallTimeNs();

/// [ns] CLOCK_MONOTONIC: for measuring durations and timeouts; never goes back.
std::int64_t steadyTimeNs();

/// [s] The CPU time in a resource usage (getrusage, wait4): user plus system.
double cpuSeconds(const ::rusage& usage);
/// [s] The CPU time this process took so far, all its threads.
double processCpuSeconds();
/// [MiB] The most memory held resident at once in a resource usage (its maximum resident set).
double maxResidentMiB(const ::rusage& usage);
/// [MiB] The most memory this process held resident so far.
double processMaxResidentMiB();
/// The times the threads of a resource usage gave up the processor to wait (its voluntary
/// context switches: for a sample, a lock, a timeout), each ended by a wake-up.
std::uint64_t waits(const ::rusage& usage);
/// The times this process's threads waited so far.
std::uint64_t processWaits();

constexpr double toSeconds(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }

/// Rounds to the nearest nanosecond. The caller checks that `seconds` is finite.
inline std::int64_t toNanoseconds(double seconds)
{
  return static_cast<std::int64_t>(std::llround(seconds * 1e9));
}

}  // namespace quad::common
