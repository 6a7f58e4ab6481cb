// SPDX-License-Identifier: BSD-3-Clause
#include "quad/world/world_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <set>
#include <sstream>

#include "quad/common/yaml_input.hpp"
#include "quad/world/scan_file.hpp"

namespace quad::world {

namespace {

/// The common reader plus the one shape only worlds have: a 3-vector.
class Reader : public common::YamlReader {
public:
  using YamlReader::YamlReader;

  std::optional<Vector3> vector3(const YAML::Node& node, const std::string& key)
  {
    const auto v = numbers(node, key, 3, -1e6, 1e6);
    return v ? std::optional<Vector3>(Vector3((*v)[0], (*v)[1], (*v)[2])) : std::nullopt;
  }
};

/// Uniform in [0, 1) from 53 bits: the same numbers on every platform for a seed.
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }
double uniform(std::mt19937_64& rng, double lo, double hi) { return lo + (hi - lo) * unit(rng); }

bool clearOf(const Vector3& p, double radius, const Vector3& start, const Vector3& goal, double clearance)
{
  const auto horizontal = [](const Vector3& a, const Vector3& b) { return std::hypot(a.x() - b.x(), a.y() - b.y()); };
  return horizontal(p, start) > radius + clearance && horizontal(p, goal) > radius + clearance;
}

void parseObstacle(Reader& r, YAML::Node node, const std::string& key, std::vector<Obstacle>& out)
{
  if (!node.IsMap()) {
    r.problem(key, node, "expected a map with a type");
    return;
  }
  const std::string type = node["type"].IsScalar() ? node["type"].Scalar() : "";
  if (type == "box") {
    r.onlyKeys(node, key + ".", {"type", "center", "size", "yaw"});
    const auto c = r.vector3(node["center"], key + ".center");
    const auto s = r.numbers(node["size"], key + ".size", 3, 1e-6, 1e5);
    const auto yaw = r.number(node["yaw"], key + ".yaw", 0.0, -100.0, 100.0);
    if (c && s && yaw) {
      out.push_back(Obstacle::makeBox({*c, Vector3((*s)[0], (*s)[1], (*s)[2]), *yaw}));
    }
  } else if (type == "cylinder") {
    r.onlyKeys(node, key + ".", {"type", "center", "radius", "height"});
    const auto c = r.numbers(node["center"], key + ".center", 2, -1e6, 1e6);
    const auto radius = r.number(node["radius"], key + ".radius", std::nullopt, 1e-6, 1e5);
    const auto height = r.number(node["height"], key + ".height", std::nullopt, 1e-6, 1e5);
    if (c && radius && height) {
      out.push_back(Obstacle::makeCylinder({(*c)[0], (*c)[1], *radius, *height}));
    }
  } else if (type == "sphere") {
    r.onlyKeys(node, key + ".", {"type", "center", "radius"});
    const auto c = r.vector3(node["center"], key + ".center");
    const auto radius = r.number(node["radius"], key + ".radius", std::nullopt, 1e-6, 1e5);
    if (c && radius) {
      out.push_back(Obstacle::makeSphere({*c, *radius}));
    }
  } else {
    r.problem(key + ".type", node["type"], "expected box, cylinder or sphere");
  }
}

void generate(Reader& r, YAML::Node node, const std::string& key, const Vector3& start,
              const Vector3& goal, std::vector<Obstacle>& out)
{
  if (!node.IsMap()) {
    r.problem(key, node, "expected a map with a type");
    return;
  }
  const std::string type = node["type"].IsScalar() ? node["type"].Scalar() : "";
  const auto seed = r.number(node["seed"], key + ".seed", std::nullopt, 0.0, 4294967295.0);
  const auto lo = r.numbers(node["min"], key + ".min", 2, -1e6, 1e6);
  const auto hi = r.numbers(node["max"], key + ".max", 2, -1e6, 1e6);
  const auto clearance = r.number(node["clearance"], key + ".clearance", 2.0, 0.0, 1e3);
  if (lo && hi && ((*lo)[0] >= (*hi)[0] || (*lo)[1] >= (*hi)[1])) {
    r.problem(key + ".max", node["max"], "must exceed min on x and y");
  }
  if (type == "forest") {
    r.onlyKeys(node, key + ".", {"type", "seed", "min", "max", "density", "radius", "height", "clearance", "gap"});
    const auto density = r.number(node["density"], key + ".density", std::nullopt, 1e-6, 10.0);
    const auto radius = r.range(node["radius"], key + ".radius", 1e-6, 100.0);
    const auto height = r.range(node["height"], key + ".height", 1e-6, 1e4);
    // Without a gap (-1) trees may overlap (the shipped forests); with one, each is drawn again
    // until it keeps at least that much from every tree before it (the benchmark's forests).
    const double gap = node["gap"].IsDefined() ? r.number(node["gap"], key + ".gap", 0.0, 0.0, 1e3).value_or(0.0) : -1.0;
    if (!r.ok() || !seed || !lo || !hi || !density || !radius || !height || !clearance) {
      return;
    }
    std::mt19937_64 rng(static_cast<std::uint64_t>(*seed));
    const double area = ((*hi)[0] - (*lo)[0]) * ((*hi)[1] - (*lo)[1]);
    const auto count = static_cast<long>(std::lround(*density * area));
    constexpr int kDraws = 1000;  // a tree drawn this often without room is a forest too dense for its gap
    std::vector<Cylinder> trees;
    for (long k = 0; k < count; ++k) {
      for (int draw = 0;; ++draw) {
        const double x = uniform(rng, (*lo)[0], (*hi)[0]);
        const double y = uniform(rng, (*lo)[1], (*hi)[1]);
        const double rad = uniform(rng, radius->first, radius->second);
        const double h = uniform(rng, height->first, height->second);
        const bool apart = gap < 0.0 || std::none_of(trees.begin(), trees.end(), [&](const Cylinder& t) {
          return std::hypot(t.x - x, t.y - y) < t.radius + rad + gap;
        });
        if (apart) {
          trees.push_back({x, y, rad, h});
          if (clearOf({x, y, 0.0}, rad, start, goal, *clearance)) {
            out.push_back(Obstacle::makeCylinder(trees.back()));
          }
          break;
        }
        if (draw + 1 == kDraws) {
          r.problem(key + ".gap", node["gap"],
                    "no room for tree " + std::to_string(k + 1) + " of " + std::to_string(count) + " with that gap");
          return;
        }
      }
    }
  } else if (type == "walls") {
    r.onlyKeys(node, key + ".", {"type", "seed", "min", "max", "count", "gap", "thickness", "height", "clearance"});
    const auto count = r.number(node["count"], key + ".count", std::nullopt, 1.0, 1000.0);
    const auto gap = r.number(node["gap"], key + ".gap", std::nullopt, 1e-3, 1e4);
    const auto thickness = r.number(node["thickness"], key + ".thickness", 0.3, 1e-3, 100.0);
    const auto height = r.number(node["height"], key + ".height", std::nullopt, 1e-3, 1e4);
    if (!r.ok() || !seed || !lo || !hi || !count || !gap || !thickness || !height || !clearance) {
      return;
    }
    if (*gap >= (*hi)[1] - (*lo)[1]) {
      r.problem(key + ".gap", node["gap"], "wider than the walls' span in y");
      return;
    }
    std::mt19937_64 rng(static_cast<std::uint64_t>(*seed));
    const int n = static_cast<int>(*count);
    for (int k = 0; k < n; ++k) {
      // Walls across y at evenly spaced x, each with one gap at a random position.
      const double x = (*lo)[0] + ((*hi)[0] - (*lo)[0]) * (k + 0.5) / n;
      const double gap_lo = uniform(rng, (*lo)[1], (*hi)[1] - *gap);
      const double gap_hi = gap_lo + *gap;
      for (const auto& [y0, y1] : {std::pair((*lo)[1], gap_lo), std::pair(gap_hi, (*hi)[1])}) {
        if (y1 - y0 < 1e-6) {
          continue;
        }
        const Box b{Vector3(x, (y0 + y1) / 2.0, *height / 2.0), Vector3(*thickness, y1 - y0, *height), 0.0};
        const Obstacle wall = Obstacle::makeBox(b);
        if (wall.signedDistance(start) > *clearance && wall.signedDistance(goal) > *clearance) {
          out.push_back(wall);
        }
      }
    }
  } else {
    r.problem(key + ".type", node["type"], "expected forest or walls");
  }
}

void parseMap(Reader& r, YAML::Node node, const std::string& key, const std::filesystem::path& base_dir,
              std::vector<VoxelMap>& out)
{
  if (!node.IsMap()) {
    r.problem(key, node, "expected {file: F, pose: [x, y, z, yaw], resolution: R}");
    return;
  }
  r.onlyKeys(node, key + ".", {"file", "pose", "resolution"});
  if (!node["file"].IsScalar() || node["file"].Scalar().empty()) {
    r.problem(key + ".file", node["file"], "expected the path of a .bt, .ot, .ply or .pcd file");
    return;
  }
  const std::filesystem::path file = base_dir / node["file"].Scalar();
  const auto pose = node["pose"].IsDefined() ? r.numbers(node["pose"], key + ".pose", 4, -1e6, 1e6)
                                             : std::optional<std::vector<double>>(std::vector<double>{0, 0, 0, 0});
  const auto resolution = r.number(node["resolution"], key + ".resolution", 0.0, 0.0, 100.0);
  if (!pose || !resolution) {
    return;
  }
  if (*resolution > 0.0 && *resolution < 0.005) {
    r.problem(key + ".resolution", node["resolution"], "finer than 5 mm");
    return;
  }
  ScanPlacement placement;
  placement.position = Vector3((*pose)[0], (*pose)[1], (*pose)[2]);
  placement.yaw = (*pose)[3];
  placement.resolution = *resolution;
  try {
    out.push_back(loadScan(file, placement));
  } catch (const ScanError& e) {
    r.problem(key + ".file", node["file"], e.what());
  }
}

}  // namespace

World parseWorld(std::string_view yaml_text, std::string_view origin)
{
  const std::filesystem::path from(origin);
  return parseWorld(yaml_text, origin, from.has_parent_path() ? from.parent_path() : std::filesystem::path("."));
}

World parseWorld(std::string_view yaml_text, std::string_view origin, const std::filesystem::path& base_dir)
{
  Reader r(origin);
  YAML::Node root = common::parseYaml(yaml_text, origin);  // not const: a missing key must read as undefined, not invalid
  if (!root.IsMap()) {
    r.problem("(top level)", root, "expected a map with bounds, start, goal");
    r.throwIfAny();
  }
  r.onlyKeys(root, "", {"bounds", "start", "goal", "obstacles", "generators", "maps", "index_cell_size"});
  std::vector<VoxelMap> maps;
  YAML::Node scans = root["maps"];
  if (scans.IsDefined() && !scans.IsNull() && !scans.IsSequence()) {
    r.problem("maps", scans, "expected a list");
  } else if (scans.IsSequence()) {
    for (std::size_t i = 0; i < scans.size(); ++i) {
      parseMap(r, scans[i], "maps[" + std::to_string(i) + "]", base_dir, maps);
    }
  }
  YAML::Node bounds = root["bounds"];
  std::optional<Vector3> lo, hi;
  if (!bounds.IsDefined() && !maps.empty()) {
    // The maps' box: a scanned place is its own extent.
    for (const VoxelMap& m : maps) {
      Vector3 mlo, mhi;
      m.bounds(mlo, mhi);
      lo = lo ? lo->cwiseMin(mlo) : mlo;
      hi = hi ? hi->cwiseMax(mhi) : mhi;
    }
  } else if (!bounds.IsMap()) {
    r.problem("bounds", bounds, "expected {min: [x, y, z], max: [x, y, z]}");
  } else {
    r.onlyKeys(bounds, "bounds.", {"min", "max"});
    lo = r.vector3(bounds["min"], "bounds.min");
    hi = r.vector3(bounds["max"], "bounds.max");
    if (lo && hi && !((*hi - *lo).array() > 0.0).all()) {
      r.problem("bounds.max", bounds["max"], "must exceed bounds.min on every axis");
    }
  }
  const auto start = r.vector3(root["start"], "start");
  const auto goal = r.vector3(root["goal"], "goal");
  const auto cell = r.number(root["index_cell_size"], "index_cell_size", 2.0, 0.05, 1000.0);
  if (lo && hi && start && !Bounds{*lo, *hi}.contains(*start)) {
    r.problem("start", root["start"], "outside the bounds");
  }
  if (lo && hi && goal && !Bounds{*lo, *hi}.contains(*goal)) {
    r.problem("goal", root["goal"], "outside the bounds");
  }
  std::vector<Obstacle> obstacles;
  YAML::Node listed = root["obstacles"];
  if (listed.IsDefined() && !listed.IsNull() && !listed.IsSequence()) {
    r.problem("obstacles", listed, "expected a list");
  } else if (listed.IsSequence()) {
    for (std::size_t i = 0; i < listed.size(); ++i) {
      parseObstacle(r, listed[i], "obstacles[" + std::to_string(i) + "]", obstacles);
    }
  }
  YAML::Node generators = root["generators"];
  if (generators.IsDefined() && !generators.IsNull() && !generators.IsSequence()) {
    r.problem("generators", generators, "expected a list");
  } else if (generators.IsSequence() && start && goal) {
    for (std::size_t i = 0; i < generators.size(); ++i) {
      generate(r, generators[i], "generators[" + std::to_string(i) + "]", *start, *goal, obstacles);
    }
  }
  r.throwIfAny();
  return World(Bounds{*lo, *hi}, *start, *goal, std::move(obstacles), *cell, std::move(maps));
}

World loadWorld(const std::filesystem::path& file)
{
  return parseWorld(common::readTextFile(file), file.string(), file.parent_path().empty() ? "." : file.parent_path());
}

}  // namespace quad::world
