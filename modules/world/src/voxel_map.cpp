// SPDX-License-Identifier: BSD-3-Clause
#include "quad/world/voxel_map.hpp"

#include "quad/world/ray_box.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace quad::world {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

bool zyxLess(const VoxelIndex& a, const VoxelIndex& b)
{
  return std::array{a.z(), a.y(), a.x()} < std::array{b.z(), b.y(), b.x()};
}

}  // namespace

VoxelMap::VoxelMap(std::string name, const geometry::VoxelGrid& grid, std::vector<VoxelIndex> occupied)
    : name_(std::move(name)), grid_(grid), occupied_(std::move(occupied))
{
  if (occupied_.empty()) {
    throw std::invalid_argument(name_ + ": no occupied voxel");
  }
  std::sort(occupied_.begin(), occupied_.end(), zyxLess);
  occupied_.erase(std::unique(occupied_.begin(), occupied_.end()), occupied_.end());
  VoxelIndex lo = occupied_.front();
  VoxelIndex hi = occupied_.front();
  for (const VoxelIndex& i : occupied_) {
    lo = lo.cwiseMin(i);
    hi = hi.cwiseMax(i);
  }
  origin_ = lo;
  dims_ = hi - lo + VoxelIndex::Ones();
  const std::int64_t cells = std::int64_t{dims_.x()} * dims_.y() * dims_.z();
  if (cells > kMaxCells) {
    throw std::invalid_argument(name_ + ": its occupied voxels span " + std::to_string(dims_.x()) + " x " +
                                std::to_string(dims_.y()) + " x " + std::to_string(dims_.z()) + " voxels of " +
                                std::to_string(grid_.resolution()) + " m, more than " + std::to_string(kMaxCells) +
                                ": choose a coarser resolution");
  }
  bits_.assign(static_cast<std::size_t>((cells + 63) / 64), 0U);
  for (const VoxelIndex& i : occupied_) {
    const auto c = static_cast<std::uint64_t>(cellOf(i));
    bits_[c / 64] |= std::uint64_t{1} << (c % 64);
  }
}

bool VoxelMap::inBox(const VoxelIndex& i) const
{
  const VoxelIndex r = i - origin_;
  return (r.array() >= 0).all() && (r.array() < dims_.array()).all();
}

std::int64_t VoxelMap::cellOf(const VoxelIndex& i) const
{
  const VoxelIndex r = i - origin_;
  return (std::int64_t{r.z()} * dims_.y() + r.y()) * dims_.x() + r.x();
}

bool VoxelMap::occupied(const VoxelIndex& i) const
{
  if (!inBox(i)) {
    return false;
  }
  const auto c = static_cast<std::uint64_t>(cellOf(i));
  return ((bits_[c / 64] >> (c % 64)) & 1U) != 0U;
}

void VoxelMap::bounds(Vector3& lo, Vector3& hi) const
{
  lo = origin_.cast<double>() * resolution();
  hi = (origin_ + dims_).cast<double>() * resolution();
}

std::optional<double> VoxelMap::raycast(const Vector3& o, const Vector3& d, double t_max) const
{
  Vector3 lo;
  Vector3 hi;
  bounds(lo, hi);
  // Clip the ray to the map's box; nothing outside it is solid.
  const auto span = rayBoxSpan(o, d, lo, hi, t_max);
  if (!span) {
    return std::nullopt;
  }
  const auto [t0, t1] = *span;
  // The voxel where the ray enters the box; rounding at its faces may land one voxel out.
  VoxelIndex v = grid_.toIndex(o + t0 * d).cwiseMax(origin_).cwiseMin(origin_ + dims_ - VoxelIndex::Ones());
  if (occupied(v)) {
    return t0;
  }
  const double res = resolution();
  Eigen::Vector3i step;
  Vector3 t_next;
  Vector3 t_delta;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-300) {
      step[a] = 0;
      t_next[a] = kInfinity;
      t_delta[a] = kInfinity;
      continue;
    }
    step[a] = d[a] > 0.0 ? 1 : -1;
    const double boundary = (v[a] + (step[a] > 0 ? 1 : 0)) * res;
    t_next[a] = (boundary - o[a]) / d[a];
    t_delta[a] = res / std::abs(d[a]);
  }
  while (true) {
    int a = 0;
    t_next.minCoeff(&a);
    const double t = t_next[a];
    if (t > t1) {
      return std::nullopt;
    }
    v[a] += step[a];
    if (!inBox(v)) {
      return std::nullopt;
    }
    if (occupied(v)) {
      return std::max(t, t0);
    }
    t_next[a] += t_delta[a];
  }
}

int VoxelMap::firstLayerAbove(double z) const
{
  // voxel layer k's top is (k + 1)·res; rounding within a micrometre counts as at z
  const double k = std::floor((z + 1e-6) / resolution());
  return static_cast<int>(std::clamp(k, -2e9, 2e9));
}

std::optional<double> VoxelMap::topBelow(const Vector3& p, double reach, double z_max, double floor) const
{
  const int k_top = std::min(firstLayerAbove(z_max) - 1, origin_.z() + dims_.z() - 1);
  const int k_bottom = std::max(firstLayerAbove(floor), origin_.z());
  if (k_top < k_bottom) {
    return std::nullopt;
  }
  const double res = resolution();
  const VoxelIndex lo = grid_.toIndex(p - Vector3(reach, reach, 0.0)).cwiseMax(origin_);
  const VoxelIndex hi = grid_.toIndex(p + Vector3(reach, reach, 0.0)).cwiseMin(origin_ + dims_ - VoxelIndex::Ones());
  std::optional<int> best;
  for (int y = lo.y(); y <= hi.y(); ++y) {
    for (int x = lo.x(); x <= hi.x(); ++x) {
      const double dx = std::max({x * res - p.x(), p.x() - (x + 1) * res, 0.0});
      const double dy = std::max({y * res - p.y(), p.y() - (y + 1) * res, 0.0});
      if (std::hypot(dx, dy) > reach) {
        continue;
      }
      for (int z = k_top; z >= std::max(k_bottom, best.value_or(k_bottom - 1) + 1); --z) {
        if (occupied(VoxelIndex(x, y, z))) {
          best = z;
          break;
        }
      }
    }
  }
  if (best) {
    return (*best + 1) * res;
  }
  return std::nullopt;
}

std::optional<double> VoxelMap::distance(const Vector3& p, double cap, double above) const
{
  Vector3 lo;
  Vector3 hi;
  bounds(lo, hi);
  const double to_box = (lo - p).cwiseMax(p - hi).cwiseMax(0.0).norm();
  if (to_box > cap) {
    return std::nullopt;  // the whole map is farther
  }
  cap = std::min(cap, to_box + (hi - lo).norm());  // nothing of the map lies farther: an infinite cap ends

  const double res = resolution();
  const VoxelIndex c = grid_.toIndex(p);
  const VoxelIndex box_hi = origin_ + dims_ - VoxelIndex::Ones();
  const int z_first = std::max(origin_.z(), firstLayerAbove(above));
  double best = kInfinity;
  const auto consider = [&](int x, int y, int z) {
    const VoxelIndex v(x, y, z);
    if (occupied(v)) {
      const Vector3 v_lo = v.cast<double>() * res;
      best = std::min(best, (v_lo - p).cwiseMax(p - (v_lo + Vector3::Constant(res))).cwiseMax(0.0).norm());
    }
  };
  const int k_max = static_cast<int>(std::ceil(cap / res)) + 1;
  for (int k = 0; k <= k_max; ++k) {
    // Every voxel k steps away (Chebyshev) is at least (k − 1)·res from p, which lies in c.
    if ((k - 1) * res > std::min(best, cap)) {
      break;
    }
    const int z0 = std::max(c.z() - k, z_first);
    const int z1 = std::min(c.z() + k, box_hi.z());
    const int y0 = std::max(c.y() - k, origin_.y());
    const int y1 = std::min(c.y() + k, box_hi.y());
    const int x0 = std::max(c.x() - k, origin_.x());
    const int x1 = std::min(c.x() + k, box_hi.x());
    for (int z = z0; z <= z1; ++z) {
      for (int y = y0; y <= y1; ++y) {
        if (std::abs(z - c.z()) == k || std::abs(y - c.y()) == k) {
          for (int x = x0; x <= x1; ++x) {
            consider(x, y, z);
          }
        } else {
          // inside the shell's faces on z and y: only its two x faces
          if (c.x() - k >= origin_.x()) {
            consider(c.x() - k, y, z);
          }
          if (k > 0 && c.x() + k <= box_hi.x()) {
            consider(c.x() + k, y, z);
          }
        }
      }
    }
  }
  if (best <= cap) {
    return best;
  }
  return std::nullopt;
}

}  // namespace quad::world
