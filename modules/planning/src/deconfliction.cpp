// SPDX-License-Identifier: BSD-3-Clause
#include "quad/planning/deconfliction.hpp"

#include <algorithm>
#include <cmath>

#include "quad/common/time.hpp"
#include "quad/geometry/polyline.hpp"

namespace quad::planning {

namespace {

/// [m] The distance from p to the segment a-b.
double segmentDistance(const Vector3& p, const Vector3& a, const Vector3& b)
{
  const Vector3 ab = b - a;
  const double length2 = ab.squaredNorm();
  const double s = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

}  // namespace

std::vector<Cell> cellsNear(const Lattice& lattice, const std::vector<Vector3>& path, double lookahead, double clearance)
{
  std::vector<Cell> cells;
  if (path.empty()) {
    return cells;
  }
  std::vector<Vector3> tube = geometry::truncated(path, lookahead);
  if (tube.size() == 1) {
    tube.push_back(tube.front());
  }
  const geometry::VoxelGrid& grid = lattice.grid();
  for (std::size_t k = 1; k < tube.size(); ++k) {
    const Vector3& a = tube[k - 1];
    const Vector3& b = tube[k];
    const VoxelIndex lo = grid.toIndex(a.cwiseMin(b) - Vector3::Constant(clearance));
    const VoxelIndex hi = grid.toIndex(a.cwiseMax(b) + Vector3::Constant(clearance));
    for (int z = lo.z(); z <= hi.z(); ++z) {
      for (int y = lo.y(); y <= hi.y(); ++y) {
        for (int x = lo.x(); x <= hi.x(); ++x) {
          const VoxelIndex v(x, y, z);
          const auto c = lattice.cell(v);
          if (c && segmentDistance(grid.centre(v), a, b) <= clearance) {
            cells.push_back(*c);
          }
        }
      }
    }
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  return cells;
}

Deconfliction::Deconfliction(std::uint32_t self, FleetRule rule, double inflation, double radius)
    : self_(self), rule_(rule), inflation_(inflation), radius_(radius)
{
}

void Deconfliction::onPath(std::uint32_t vehicle, std::int64_t stamp_ns, std::vector<Vector3> waypoints)
{
  if (vehicle == self_ || !yieldsTo(self_, vehicle)) {
    return;
  }
  std::vector<Heard>& heard = paths_[vehicle];
  if (!heard.empty() && heard.back().stamp_ns >= stamp_ns) {
    return;
  }
  // Paths come every republish period or sooner: a few cover the delay before one takes effect.
  constexpr std::size_t kKept = 8;
  if (heard.size() == kKept) {
    heard.erase(heard.begin());
  }
  heard.push_back({stamp_ns, std::move(waypoints)});
}

const Deconfliction::Heard* Deconfliction::inEffect(const std::vector<Heard>& heard, std::int64_t now_ns) const
{
  for (auto it = heard.rbegin(); it != heard.rend(); ++it) {
    if (it->stamp_ns + kPathEffectDelayNs <= now_ns) {
      const bool fresh = now_ns - it->stamp_ns <= common::toNanoseconds(rule_.path_timeout_s);
      return fresh && !it->waypoints.empty() ? &*it : nullptr;
    }
  }
  return nullptr;
}

std::vector<std::uint32_t> Deconfliction::yieldingTo(std::int64_t now_ns) const
{
  std::vector<std::uint32_t> out;
  for (const auto& [vehicle, heard] : paths_) {
    if (inEffect(heard, now_ns) != nullptr) {
      out.push_back(vehicle);
    }
  }
  return out;
}

std::vector<Cell> Deconfliction::keepOut(const Lattice& lattice, std::int64_t now_ns) const
{
  std::vector<Cell> cells;
  for (const auto& [vehicle, heard] : paths_) {
    if (const Heard* path = inEffect(heard, now_ns)) {
      const std::vector<Cell> tube = cellsNear(lattice, path->waypoints, rule_.lookahead, clearance());
      cells.insert(cells.end(), tube.begin(), tube.end());
    }
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  return cells;
}

}  // namespace quad::planning
