// SPDX-License-Identifier: BSD-3-Clause
#include "quad/planning/known_space.hpp"

#include <algorithm>
#include <cmath>

#include "quad/geometry/inflation.hpp"

namespace quad::planning {

std::optional<double> knownFreeLength(const DStarLite& planner, const std::vector<Vector3>& waypoints,
                                      const Vector3& vehicle_W, const KnownSpaceCheck& check)
{
  const geometry::VoxelGrid& grid = planner.lattice().grid();
  const std::vector<VoxelIndex> ball = geometry::inflationOffsets(check.radius, grid.resolution());
  // Read for the path's voxel `v`, `u` is known free, or the vehicle's own volume; and the voxel
  // the vehicle is in passes whatever its tube holds: the vehicle is there already, beside an
  // obstacle maybe (with one half diagonal less than that tube reaches, a vehicle stopped beside
  // one never had a path known free again), or where its camera never looked (behind and below
  // it, when it took over in the air: the tube's far corners lie past the own radius). The
  // voxels after it are read as ever.
  const VoxelIndex own = grid.toIndex(vehicle_W);
  const auto known_free = [&](const VoxelIndex& v, const VoxelIndex& u) {
    const Occupancy state = planner.voxelState(u);
    return state == Occupancy::kFree || v == own ||
           (grid.centre(u) - vehicle_W).norm() <= check.own_radius;
  };
  // Every voxel the polyline passes through, in order, with the arc length where the path
  // enters it (Amanatides & Woo's traversal): the frontier is where it enters the first
  // voxel whose neighbourhood holds a voxel not known free.
  std::optional<VoxelIndex> last;
  double s = 0.0;  // arc length at the start of the segment
  const double res = grid.resolution();
  for (std::size_t i = 0; i + 1 < waypoints.size() || (i == 0 && waypoints.size() == 1); ++i) {
    const Vector3 a = waypoints[i];
    const Vector3 b = i + 1 < waypoints.size() ? waypoints[i + 1] : a;
    const double length = (b - a).norm();
    const Vector3 d = length > 0.0 ? Vector3((b - a) / length) : Vector3::UnitX();
    VoxelIndex v = grid.toIndex(a);
    Eigen::Vector3i step = Eigen::Vector3i::Zero();
    Vector3 t_max = Vector3::Constant(kInfinity);
    Vector3 t_delta = Vector3::Constant(kInfinity);
    for (int axis = 0; axis < 3; ++axis) {
      if (d[axis] > 1e-12) {
        step[axis] = 1;
        t_max[axis] = ((v[axis] + 1) * res - a[axis]) / d[axis];
        t_delta[axis] = res / d[axis];
      } else if (d[axis] < -1e-12) {
        step[axis] = -1;
        t_max[axis] = (v[axis] * res - a[axis]) / d[axis];
        t_delta[axis] = -res / d[axis];
      }
    }
    double entry = 0.0;  // where the path enters v, along this segment
    for (;;) {
      if (s + entry > check.horizon) {
        return std::nullopt;
      }
      if (!last || v != *last) {
        last = v;
        for (const VoxelIndex& o : ball) {
          if (!known_free(v, v + o)) {
            return s + entry;
          }
        }
      }
      int axis = 0;
      t_max.minCoeff(&axis);
      if (!(t_max[axis] <= length)) {
        break;  // the segment ends in v
      }
      entry = t_max[axis];
      v[axis] += step[axis];
      t_max[axis] += t_delta[axis];
    }
    s += length;
  }
  return std::nullopt;
}

}  // namespace quad::planning
