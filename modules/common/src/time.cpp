// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/time.hpp"

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

}  // namespace quad::common
