// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The vehicle's recent poses, looked up at a depth cloud's time: the cloud carries the
/// sensor's pose on the body, the vehicle state says where the body was. Between two states
/// the pose is interpolated (position linearly, attitude along the shortest arc); a little
/// past the newest one it is carried on at the newest velocity.

#include <cstdint>
#include <deque>
#include <optional>

#include "quad/geometry/cspace.hpp"

namespace quad::mapping {

struct PoseHistoryConfig {
  std::int64_t window_ns = 2'000'000'000;   ///< states kept this far behind the newest
  std::int64_t max_gap_ns = 100'000'000;    ///< two states further apart do not interpolate
  std::int64_t max_ahead_ns = 10'000'000;   ///< how far past the newest state a pose is carried
};

class PoseHistory {
public:
  explicit PoseHistory(PoseHistoryConfig config = {}) : config_(config) {}

  /// The body pose at t_ns with the body's world velocity v_W [m/s]; false (nothing kept) when
  /// not newer than the newest.
  bool add(std::int64_t t_ns, const geometry::Pose3& pose_WB, const geometry::Vector3& v_W);
  /// The body pose at t_ns; nothing when t_ns is older than the window, falls in a gap longer
  /// than max_gap_ns, or lies more than max_ahead_ns past the newest state.
  std::optional<geometry::Pose3> at(std::int64_t t_ns) const;
  /// The newest state's time; -1 before the first.
  std::int64_t newestNs() const { return samples_.empty() ? -1 : samples_.back().t_ns; }

private:
  struct Sample {
    std::int64_t t_ns;
    geometry::Pose3 pose;
    geometry::Vector3 v_W;
  };
  PoseHistoryConfig config_;
  std::deque<Sample> samples_;
};

}  // namespace quad::mapping
