#include "quad/planning/known_space.hpp"

#include <algorithm>
#include <cmath>

#include "quad/geometry/inflation.hpp"

namespace quad::planning {

std::optional<double> knownFreeLength(const DStarLite& planner, const std::vector<Vector3>& waypoints,
                                      const Vector3& vehicle_W, const KnownSpaceCheck& check)
{
  const geometry::VoxelGrid& grid = planner.lattice().grid();
  const double step = grid.resolution() / 4.0;
  const std::vector<VoxelIndex> ball = geometry::inflationOffsets(check.radius, grid.resolution());
  const auto known_free = [&](const VoxelIndex& v) {
    return planner.voxelState(v) == Occupancy::kFree || (grid.centre(v) - vehicle_W).norm() <= check.own_radius;
  };
  std::optional<VoxelIndex> last;
  double s = 0.0;  // arc length of the last point found clear
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    const Vector3 a = waypoints[i];
    const Vector3 b = i + 1 < waypoints.size() ? waypoints[i + 1] : a;
    const double length = (b - a).norm();
    const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
    for (int k = 0; k <= n; ++k) {
      const double along = length * k / n;
      if (s + along > check.horizon) {
        return std::nullopt;
      }
      const VoxelIndex v = grid.toIndex(a + (b - a) * (along / std::max(length, 1e-12)));
      if (last && v == *last) {
        continue;
      }
      last = v;
      for (const VoxelIndex& d : ball) {
        if (!known_free(v + d)) {
          return std::max(0.0, s + along - step);
        }
      }
    }
    s += length;
  }
  return std::nullopt;
}

}  // namespace quad::planning
