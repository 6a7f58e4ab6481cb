// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/time.hpp"

#include <sys/resource.h>

#include <ctime>

namespace quad::common {
namespace {
std::int64_t read(clockid_t clock)
{
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * kNanosecondsPerSecond + ts.tv_nsec;
}
}  // namespace

std::int64_t wallTimeNs() { return read(CLOCK_REALTIME); }
std::int64_t steadyTimeNs() { return read(CLOCK_MONOTONIC); }

double cpuSeconds(const ::rusage& usage)
{
  const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

double processCpuSeconds()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return cpuSeconds(usage);
}

double maxResidentMiB(const ::rusage& usage) { return static_cast<double>(usage.ru_maxrss) / 1024.0; }  // Linux: KiB

double processMaxResidentMiB()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return maxResidentMiB(usage);
}

std::uint64_t waits(const ::rusage& usage) { return static_cast<std::uint64_t>(usage.ru_nvcsw); }

std::uint64_t processWaits()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return waits(usage);
}

}  // namespace quad::common
