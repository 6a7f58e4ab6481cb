// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant/command_guard.hpp"

#include <algorithm>
#include <cmath>

namespace quad::plant {

CommandGuard::CommandGuard(const vehicle::VehicleParams& vehicle, std::int64_t timeout_ns,
                           std::int64_t failsafe_ns)
    : min_(vehicle.rotor_speed_min),
      max_(vehicle.rotor_speed_max),
      timeout_ns_(timeout_ns),
      failsafe_ns_(failsafe_ns)
{
}

CommandGuard::Verdict CommandGuard::submit(const RotorArray& speeds, bool armed, std::int64_t stamp_ns,
                                           std::int64_t now_ns)
{
  if (std::any_of(speeds.begin(), speeds.end(), [](double w) { return !std::isfinite(w); })) {
    ++counters_.rejected_invalid;
    return Verdict::kRejectedInvalid;
  }
  if (now_ns - stamp_ns > timeout_ns_) {
    ++counters_.rejected_late;
    return Verdict::kRejectedLate;
  }
  if (have_command_ && stamp_ns < held_stamp_ns_) {
    ++counters_.rejected_old;
    return Verdict::kRejectedOld;
  }
  bool clamped = false;
  RotorArray next{};
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    next[i] = std::clamp(speeds[i], min_, max_);
    clamped = clamped || next[i] != speeds[i];
  }
  held_ = next;
  // Thrust goes with the square of the speed: the root mean square keeps the total.
  double sum_sq = 0.0;
  for (const double w : next) {
    sum_sq += w * w;
  }
  balanced_.fill(std::sqrt(sum_sq / static_cast<double>(next.size())));
  armed_ = armed;
  have_command_ = true;
  held_stamp_ns_ = stamp_ns;
  if (clamped) {
    ++counters_.clamped;
    return Verdict::kClamped;
  }
  ++counters_.accepted;
  return Verdict::kAccepted;
}

bool CommandGuard::stale(std::int64_t now_ns) const
{
  return !have_command_ || now_ns - held_stamp_ns_ > timeout_ns_;
}

RotorArray CommandGuard::command(std::int64_t now_ns)
{
  if (have_command_ && stale(now_ns)) {
    ++counters_.stale_steps;
  }
  if (!have_command_ || !armed_) {
    return RotorArray{};
  }
  if (now_ns - held_stamp_ns_ > failsafe_ns_) {
    ++counters_.failsafe_steps;
    return balanced_;
  }
  return held_;
}

}  // namespace quad::plant
