// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The flown trajectory, thinned for viewers: a pose is kept when the vehicle has moved
/// `spacing` or turned `turn` since the last one kept. Past `max_poses` every other pose is
/// dropped (the first and the newest stay) and the spacing doubles, so a long flight stays
/// whole, coarser, in bounded memory and message size.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "quad/geometry/quaternion.hpp"

namespace quad::display {

using geometry::Quaternion;
using geometry::Vector3;

struct TracePose {
  std::int64_t t_ns = 0;  ///< the state's stamp
  Vector3 p_W = Vector3::Zero();  ///< [m]
  Quaternion q_WB;                ///< body to world
};

struct TraceParams {
  double spacing = 0.05;        ///< [m]
  double turn = 0.2;            ///< [rad]
  std::size_t max_poses = 20000;
};

class Trace {
public:
  /// Throws std::invalid_argument on a spacing or turn that is not positive, or fewer than 2 poses.
  explicit Trace(TraceParams params);

  /// Offers a sample; true when it was kept. Samples not newer than the last offered are
  /// refused (a state sent again, or out of order).
  bool add(const TracePose& pose);
  const std::vector<TracePose>& poses() const { return poses_; }
  /// The spacing now kept: `spacing`, doubled at each thinning.
  double spacing() const { return spacing_; }
  double turn() const { return turn_; }

private:
  void thin();

  TraceParams params_;
  double spacing_;
  double turn_;
  std::vector<TracePose> poses_;
  std::int64_t newest_ns_ = 0;
  bool any_ = false;
};

}  // namespace quad::display
