// SPDX-License-Identifier: BSD-3-Clause
#include "quad/world/world.hpp"

#include "quad/world/ray_box.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

namespace quad::world {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// Box frame: rotate world offsets by −yaw about z.
Vector3 toBoxFrame(const Box& b, const Vector3& v)
{
  const double c = std::cos(b.yaw);
  const double s = std::sin(b.yaw);
  return {c * v.x() + s * v.y(), -s * v.x() + c * v.y(), v.z()};
}

double boxDistance(const Vector3& local, const Vector3& half)
{
  const Vector3 d = local.cwiseAbs() - half;
  return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
}

}  // namespace

Obstacle Obstacle::makeBox(const Box& b)
{
  Obstacle o;
  o.kind = Kind::kBox;
  o.box = b;
  return o;
}

Obstacle Obstacle::makeCylinder(const Cylinder& c)
{
  Obstacle o;
  o.kind = Kind::kCylinder;
  o.cylinder = c;
  return o;
}

Obstacle Obstacle::makeSphere(const Sphere& s)
{
  Obstacle o;
  o.kind = Kind::kSphere;
  o.sphere = s;
  return o;
}

double Obstacle::signedDistance(const Vector3& p) const
{
  switch (kind) {
    case Kind::kBox:
      return boxDistance(toBoxFrame(box, p - box.center), box.size / 2.0);
    case Kind::kCylinder: {
      const double radial = std::hypot(p.x() - cylinder.x, p.y() - cylinder.y) - cylinder.radius;
      const double vertical = std::max(-p.z(), p.z() - cylinder.height);
      const double outside = std::hypot(std::max(radial, 0.0), std::max(vertical, 0.0));
      return outside + std::min(std::max(radial, vertical), 0.0);
    }
    case Kind::kSphere:
      return (p - sphere.center).norm() - sphere.radius;
  }
  return kInfinity;
}

std::optional<double> Obstacle::raycast(const Vector3& o, const Vector3& d, double t_max) const
{
  switch (kind) {
    case Kind::kBox: {
      const auto span = rayBoxSpan(toBoxFrame(box, o - box.center), toBoxFrame(box, d), -box.size / 2.0, box.size / 2.0, t_max);
      return span ? std::optional<double>(span->first) : std::nullopt;
    }
    case Kind::kCylinder: {
      if (signedDistance(o) <= 0.0) {
        return 0.0;
      }
      const double ox = o.x() - cylinder.x;
      const double oy = o.y() - cylinder.y;
      double best = kInfinity;
      // Side: |(o + t d)_xy| = r.
      const double a = d.x() * d.x() + d.y() * d.y();
      if (a > 1e-300) {
        const double b = ox * d.x() + oy * d.y();
        const double c = ox * ox + oy * oy - cylinder.radius * cylinder.radius;
        const double disc = b * b - a * c;
        if (disc >= 0.0) {
          const double t = (-b - std::sqrt(disc)) / a;  // entering: the origin is outside
          const double z = o.z() + t * d.z();
          if (t >= 0.0 && z >= 0.0 && z <= cylinder.height) {
            best = t;
          }
        }
      }
      // Caps: z = height (top) and z = 0 (bottom).
      if (std::abs(d.z()) > 1e-300) {
        for (const double plane : {cylinder.height, 0.0}) {
          const double t = (plane - o.z()) / d.z();
          if (t >= 0.0 && t < best &&
              std::hypot(ox + t * d.x(), oy + t * d.y()) <= cylinder.radius) {
            best = t;
          }
        }
      }
      if (best <= t_max) {
        return best;
      }
      return std::nullopt;
    }
    case Kind::kSphere: {
      const Vector3 oc = o - sphere.center;
      const double b = oc.dot(d);
      const double c = oc.squaredNorm() - sphere.radius * sphere.radius;
      if (c <= 0.0) {
        return 0.0;
      }
      const double disc = b * b - c;
      if (disc < 0.0) {
        return std::nullopt;
      }
      const double t = -b - std::sqrt(disc);
      if (t >= 0.0 && t <= t_max) {
        return t;
      }
      return std::nullopt;
    }
  }
  return std::nullopt;
}

void Obstacle::bounds(Vector3& lo, Vector3& hi) const
{
  switch (kind) {
    case Kind::kBox: {
      const double c = std::abs(std::cos(box.yaw));
      const double s = std::abs(std::sin(box.yaw));
      const Vector3 half(0.5 * (c * box.size.x() + s * box.size.y()),
                         0.5 * (s * box.size.x() + c * box.size.y()), 0.5 * box.size.z());
      lo = box.center - half;
      hi = box.center + half;
      return;
    }
    case Kind::kCylinder:
      lo = {cylinder.x - cylinder.radius, cylinder.y - cylinder.radius, 0.0};
      hi = {cylinder.x + cylinder.radius, cylinder.y + cylinder.radius, cylinder.height};
      return;
    case Kind::kSphere:
      lo = sphere.center - Vector3::Constant(sphere.radius);
      hi = sphere.center + Vector3::Constant(sphere.radius);
      return;
  }
}

bool Bounds::contains(const Vector3& p) const
{
  return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
}

World::World(Bounds bounds, Vector3 start, Vector3 goal, std::vector<Obstacle> obstacles,
             double cell_size, std::vector<VoxelMap> maps)
    : bounds_(std::move(bounds)),
      start_(std::move(start)),
      goal_(std::move(goal)),
      obstacles_(std::move(obstacles)),
      maps_(std::move(maps)),
      cell_size_(cell_size > 0.0 ? cell_size : 2.0)
{
  if (!((bounds_.max - bounds_.min).array() > 0.0).all()) {
    throw std::invalid_argument("World: bounds max must exceed min on every axis");
  }
  nx_ = std::max(1, static_cast<int>(std::ceil((bounds_.max.x() - bounds_.min.x()) / cell_size_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((bounds_.max.y() - bounds_.min.y()) / cell_size_)));
  cells_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
  visited_.assign(obstacles_.size(), 0);
  for (std::size_t i = 0; i < obstacles_.size(); ++i) {
    Vector3 lo, hi;
    obstacles_[i].bounds(lo, hi);
    const bool inside = lo.x() >= bounds_.min.x() && lo.y() >= bounds_.min.y() &&
                        hi.x() <= bounds_.max.x() && hi.y() <= bounds_.max.y();
    if (!inside) {
      unindexed_.push_back(static_cast<int>(i));
      continue;
    }
    for (int cy = cellY(lo.y()); cy <= cellY(hi.y()); ++cy) {
      for (int cx = cellX(lo.x()); cx <= cellX(hi.x()); ++cx) {
        cells_[static_cast<std::size_t>(cy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(cx)]
            .push_back(static_cast<int>(i));
      }
    }
  }
}

int World::cellX(double x) const
{
  return std::clamp(static_cast<int>(std::floor((x - bounds_.min.x()) / cell_size_)), 0, nx_ - 1);
}

int World::cellY(double y) const
{
  return std::clamp(static_cast<int>(std::floor((y - bounds_.min.y()) / cell_size_)), 0, ny_ - 1);
}

const std::vector<int>& World::cell(int cx, int cy) const
{
  return cells_[static_cast<std::size_t>(cy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(cx)];
}

namespace {

constexpr double kTouch = 1e-6;  // [m] a surface this close below the vehicle is under it

/// The top [m] of an obstacle: flat for boxes (yaw turns them about z) and cylinders.
double topOf(const Obstacle& o)
{
  Vector3 lo, hi;
  o.bounds(lo, hi);
  return hi.z();
}

/// The height of the obstacle's top surface within `reach` of p horizontally, if any.
std::optional<double> surfaceUnder(const Obstacle& o, const Vector3& p, double reach)
{
  switch (o.kind) {
    case Obstacle::Kind::kBox: {
      const Vector3 local = toBoxFrame(o.box, p - o.box.center);
      const double dx = std::max(std::abs(local.x()) - 0.5 * o.box.size.x(), 0.0);
      const double dy = std::max(std::abs(local.y()) - 0.5 * o.box.size.y(), 0.0);
      return std::hypot(dx, dy) <= reach ? std::optional<double>(topOf(o)) : std::nullopt;
    }
    case Obstacle::Kind::kCylinder:
      return std::hypot(p.x() - o.cylinder.x, p.y() - o.cylinder.y) <= o.cylinder.radius + reach
                 ? std::optional<double>(o.cylinder.height)
                 : std::nullopt;
    case Obstacle::Kind::kSphere: {
      // its highest point within the footprint: nearest p horizontally
      const double s = std::max(0.0, std::hypot(p.x() - o.sphere.center.x(), p.y() - o.sphere.center.y()) - reach);
      if (s > o.sphere.radius) {
        return std::nullopt;
      }
      return o.sphere.center.z() + std::sqrt(o.sphere.radius * o.sphere.radius - s * s);
    }
  }
  return std::nullopt;
}

}  // namespace

template <typename Visit>
void World::forObstaclesNear(const Vector3& p, double reach, Visit&& visit) const
{
  ++stamp_;
  const auto test = [&](int i) {
    auto& seen = visited_[static_cast<std::size_t>(i)];
    if (seen != stamp_) {
      seen = stamp_;
      visit(i, obstacles_[static_cast<std::size_t>(i)]);
    }
  };
  for (const int i : unindexed_) {
    test(i);
  }
  for (int cy = cellY(p.y() - reach); cy <= cellY(p.y() + reach); ++cy) {
    for (int cx = cellX(p.x() - reach); cx <= cellX(p.x() + reach); ++cx) {
      for (const int i : cell(cx, cy)) {
        test(i);
      }
    }
  }
}

double World::supportHeight(const Vector3& p, double radius) const
{
  const double reach = 0.5 * radius;
  const double z_max = p.z() + kTouch;
  double best = p.z() >= -kTouch ? 0.0 : bounds_.min.z();  // below the ground: the world's bottom
  forObstaclesNear(p, reach, [&](int, const Obstacle& o) {
    if (const auto top = surfaceUnder(o, p, reach); top && *top <= z_max) {
      best = std::max(best, *top);
    }
  });
  for (const VoxelMap& m : maps_) {
    if (const auto top = m.topBelow(p, reach, z_max, best)) {
      best = std::max(best, *top);
    }
  }
  return best;
}

std::vector<int> World::contacts(const Vector3& p, double radius) const
{
  return contacts(p, radius, supportHeight(p, radius));
}

std::vector<int> World::contacts(const Vector3& p, double radius, double support) const
{
  std::vector<int> out;
  forObstaclesNear(p, radius, [&](int i, const Obstacle& o) {
    if (topOf(o) > support + kTouch && o.signedDistance(p) <= radius) {
      out.push_back(i);
    }
  });
  for (std::size_t k = 0; k < maps_.size(); ++k) {
    if (maps_[k].distance(p, radius, support)) {
      out.push_back(mapId(k));
    }
  }
  const bool outside = p.x() - radius < bounds_.min.x() || p.x() + radius > bounds_.max.x() ||
                       p.y() - radius < bounds_.min.y() || p.y() + radius > bounds_.max.y() ||
                       p.z() + radius > bounds_.max.z();
  if (outside) {
    out.push_back(kBounds);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::optional<World::Nearest> World::nearest(const Vector3& p, double radius, double cap) const
{
  const double support = supportHeight(p, radius);
  std::optional<Nearest> best;
  // every obstacle: a cap may reach past the index's cells
  for (std::size_t i = 0; i < obstacles_.size(); ++i) {
    const Obstacle& o = obstacles_[i];
    if (topOf(o) <= support + kTouch) {
      continue;
    }
    if (const double d = o.signedDistance(p); d <= cap && (!best || d < best->distance)) {
      best = Nearest{d, static_cast<int>(i)};
    }
  }
  for (std::size_t k = 0; k < maps_.size(); ++k) {
    if (const auto d = maps_[k].distance(p, best ? best->distance : cap, support); d && (!best || *d < best->distance)) {
      best = Nearest{*d, mapId(k)};
    }
  }
  return best;
}

namespace {
std::optional<RayHit> groundHit(const Vector3& o, const Vector3& d, double max_range)
{
  if (d.z() < 0.0 && o.z() >= 0.0) {
    const double t = -o.z() / d.z();
    if (t <= max_range) {
      return RayHit{t, World::kGround};
    }
  }
  return std::nullopt;
}

void keepNearest(std::optional<RayHit>& best, const std::optional<double>& t, int id)
{
  if (t && (!best || *t < best->distance)) {
    best = RayHit{*t, id};
  }
}
}  // namespace

std::string World::describe(int id) const
{
  if (id == kGround) {
    return "the ground";
  }
  if (id == kBounds) {
    return "the bounds";
  }
  const auto i = static_cast<std::size_t>(id);
  if (id >= 0 && i < obstacles_.size()) {
    return "obstacle " + std::to_string(id);
  }
  if (id >= 0 && i - obstacles_.size() < maps_.size()) {
    const std::size_t k = i - obstacles_.size();
    return "map " + std::to_string(k) + " (" + std::filesystem::path(maps_[k].name()).filename().string() + ")";
  }
  return "solid " + std::to_string(id);
}

void World::raycastMaps(const Vector3& o, const Vector3& d, double max_range, std::optional<RayHit>& best) const
{
  for (std::size_t k = 0; k < maps_.size(); ++k) {
    keepNearest(best, maps_[k].raycast(o, d, best ? std::min(best->distance, max_range) : max_range), mapId(k));
  }
}

std::optional<RayHit> World::raycastBruteForce(const Vector3& o, const Vector3& d, double max_range) const
{
  std::optional<RayHit> best = groundHit(o, d, max_range);
  for (std::size_t i = 0; i < obstacles_.size(); ++i) {
    keepNearest(best, obstacles_[i].raycast(o, d, max_range), static_cast<int>(i));
  }
  raycastMaps(o, d, max_range, best);
  return best;
}

std::optional<RayHit> World::raycast(const Vector3& o, const Vector3& d, double max_range) const
{
  const bool in_grid = o.x() >= bounds_.min.x() && o.x() <= bounds_.max.x() &&
                       o.y() >= bounds_.min.y() && o.y() <= bounds_.max.y();
  if (!in_grid) {
    return raycastBruteForce(o, d, max_range);
  }
  std::optional<RayHit> best = groundHit(o, d, max_range);
  ++stamp_;
  const auto test = [&](int i) {
    auto& seen = visited_[static_cast<std::size_t>(i)];
    if (seen != stamp_) {
      seen = stamp_;
      keepNearest(best, obstacles_[static_cast<std::size_t>(i)].raycast(o, d, max_range), i);
    }
  };
  for (const int i : unindexed_) {
    test(i);
  }
  // Amanatides & Woo (1987) traversal of the x–y grid; t is the distance along d.
  int cx = cellX(o.x());
  int cy = cellY(o.y());
  const int step_x = d.x() > 0 ? 1 : -1;
  const int step_y = d.y() > 0 ? 1 : -1;
  const auto boundary = [this](int c, int step, double min) {
    return min + (c + (step > 0 ? 1 : 0)) * cell_size_;
  };
  double t_next_x = std::abs(d.x()) > 1e-300 ? (boundary(cx, step_x, bounds_.min.x()) - o.x()) / d.x() : kInfinity;
  double t_next_y = std::abs(d.y()) > 1e-300 ? (boundary(cy, step_y, bounds_.min.y()) - o.y()) / d.y() : kInfinity;
  const double dt_x = std::abs(d.x()) > 1e-300 ? cell_size_ / std::abs(d.x()) : kInfinity;
  const double dt_y = std::abs(d.y()) > 1e-300 ? cell_size_ / std::abs(d.y()) : kInfinity;
  while (true) {
    for (const int i : cell(cx, cy)) {
      test(i);
    }
    const double t_exit = std::min(t_next_x, t_next_y);
    // Anything not yet tested has its hit point in a later cell, at t >= t_exit.
    if ((best && best->distance <= t_exit) || t_exit > max_range) {
      break;
    }
    if (t_next_x < t_next_y) {
      cx += step_x;
      t_next_x += dt_x;
    } else {
      cy += step_y;
      t_next_y += dt_y;
    }
    if (cx < 0 || cx >= nx_ || cy < 0 || cy >= ny_) {
      break;  // left the grid: every indexed obstacle lies inside it
    }
  }
  raycastMaps(o, d, max_range, best);
  return best;
}

World World::withStartAndGoal(const Vector3& start, const Vector3& goal) const
{
  World copy = *this;
  copy.start_ = start;
  copy.goal_ = goal;
  return copy;
}

}  // namespace quad::world
