// SPDX-License-Identifier: BSD-3-Clause
#include "quad/mapping/mapper.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "quad/mapping/tree_bytes.hpp"

namespace quad::mapping {

namespace {

constexpr int kKeyOffset = 32768;  // OcTree's tree_max_val at depth 16

VoxelIndex indexOf(const octomap::OcTreeKey& key)
{
  return {static_cast<int>(key[0]) - kKeyOffset, static_cast<int>(key[1]) - kKeyOffset,
          static_cast<int>(key[2]) - kKeyOffset};
}

std::vector<std::string> problemsOf(const MapperConfig& c, const std::string& origin)
{
  std::vector<std::string> p;
  const auto add = [&](const char* key, double value, const std::string& why) {
    p.push_back(common::configProblem(origin, key, value, why));
  };
  if (!(c.prob_hit > 0.5)) {
    add("map.prob_hit", c.prob_hit, "must exceed 0.5, or hits would clear space");
  }
  if (!(c.prob_miss < 0.5)) {
    add("map.prob_miss", c.prob_miss, "must be below 0.5, or misses would fill space");
  }
  if (!(c.clamp_min < c.occupancy_threshold)) {
    add("map.clamp_min", c.clamp_min, "must be below map.occupancy_threshold (" + common::formatValue(c.occupancy_threshold) + ")");
  }
  if (!(c.clamp_max > c.occupancy_threshold)) {
    add("map.clamp_max", c.clamp_max, "must exceed map.occupancy_threshold (" + common::formatValue(c.occupancy_threshold) + ")");
  }
  if (!(c.min_range < c.max_range)) {
    add("map.min_range", c.min_range, "must be below map.max_range (" + common::formatValue(c.max_range) + ")");
  }
  if (c.min_z && c.max_z && !(*c.min_z < *c.max_z)) {
    add("map.min_z", *c.min_z, "must be below map.max_z (" + common::formatValue(*c.max_z) + ")");
  }
  return p;
}

}  // namespace

const common::ParamTable<MapperParams>& mapperTable()
{
  using P = MapperParams;
  static const common::ParamTable<P> table = [] {
    common::ParamTable<P> t;
    t.number("map.resolution", [](P& p) -> double& { return p.map.resolution; }, {0.01, 10.0}, "m",
             "voxel edge (the planner's lattice too)")
        .number("map.min_range", [](P& p) -> double& { return p.map.min_range; }, {0.0, 100.0}, "m",
                "closer points are dropped")
        .number("map.max_range", [](P& p) -> double& { return p.map.max_range; }, {0.1, 500.0}, "m",
                "farther points only clear space")
        .number("map.prob_hit", [](P& p) -> double& { return p.map.prob_hit; }, {0.0, 1.0}, "",
                "occupancy probability of a hit")
        .number("map.prob_miss", [](P& p) -> double& { return p.map.prob_miss; }, {0.0, 1.0}, "",
                "occupancy probability of a miss")
        .number("map.clamp_min", [](P& p) -> double& { return p.map.clamp_min; }, {0.0, 1.0}, "",
                "lower clamping of a voxel's probability")
        .number("map.clamp_max", [](P& p) -> double& { return p.map.clamp_max; }, {0.0, 1.0}, "",
                "upper clamping of a voxel's probability")
        .number("map.occupancy_threshold", [](P& p) -> double& { return p.map.occupancy_threshold; }, {0.0, 1.0}, "",
                "occupied above this probability")
        .flag("map.height_limits", [](P& p) -> bool& { return p.height_limits; },
              "drop points outside [map.min_z, map.max_z]")
        .number("map.min_z", [](P& p) -> double& { return p.min_z; }, {-1e4, 1e4}, "m",
                "lowest point kept (with height_limits)")
        .number("map.max_z", [](P& p) -> double& { return p.max_z; }, {-1e4, 1e4}, "m",
                "highest point kept (with height_limits)")
        .number("map.max_points", [](P& p) -> std::size_t& { return p.map.max_points; }, {1, 10'000'000}, "",
                "clouds with more points are refused");
    return t;
  }();
  return table;
}

MapperConfig mapperConfigFrom(const MapperParams& p, const std::string& origin)
{
  MapperConfig c = p.map;
  if (p.height_limits) {
    c.min_z = p.min_z;
    c.max_z = p.max_z;
  }
  if (auto problems = problemsOf(c, origin); !problems.empty()) {
    throw common::ConfigError(std::move(problems));
  }
  return c;
}

MapperConfig mapperConfigFrom(const common::Params& p) { return mapperConfigFrom(mapperTable().read(p), p.origin()); }

Mapper::Mapper(MapperConfig config) : config_(config), tree_(config.resolution), grid_(config.resolution)
{
  if (const auto problems = problemsOf(config_, "mapper config"); !problems.empty()) {
    throw std::invalid_argument(problems.front());
  }
  tree_.setProbHit(config_.prob_hit);
  tree_.setProbMiss(config_.prob_miss);
  tree_.setClampingThresMin(config_.clamp_min);
  tree_.setClampingThresMax(config_.clamp_max);
  tree_.setOccupancyThres(config_.occupancy_threshold);
  if (config_.box) {
    const auto lo = grid_.octomapKey(grid_.toIndex(config_.box->first));
    const auto hi = grid_.octomapKey(grid_.toIndex(config_.box->second));
    if (!lo || !hi || !(config_.box->first.array() <= config_.box->second.array()).all()) {
      throw std::invalid_argument("mapper box: empty, inverted or beyond the octree's reach");
    }
    tree_.limitTo(octomap::OcTreeKey((*lo)[0], (*lo)[1], (*lo)[2]), octomap::OcTreeKey((*hi)[0], (*hi)[1], (*hi)[2]));
  }
}

IntegrationResult Mapper::integrate(const Scan& scan)
{
  IntegrationResult out;
  if (!scan.origin_W.allFinite() || !std::isfinite(scan.max_range) || scan.max_range < 0.0) {
    out.rejection = "sensor origin or range is not finite";
    return out;
  }
  if (scan.points_W.size() > config_.max_points) {
    out.rejection = std::to_string(scan.points_W.size()) + " points exceed map.max_points (" +
                    std::to_string(config_.max_points) + ")";
    return out;
  }
  for (std::size_t i = 0; i < scan.points_W.size(); ++i) {
    if (!scan.points_W[i].allFinite()) {
      out.rejection = "point " + std::to_string(i) + " is not finite";
      return out;
    }
  }
  const double max_range = scan.max_range > 0.0 ? std::min(scan.max_range, config_.max_range) : config_.max_range;
  octomap::Pointcloud cloud;
  cloud.reserve(scan.points_W.size());
  const double min_range2 = config_.min_range * config_.min_range;
  const bool limited = min_range2 > 0.0 || config_.min_z || config_.max_z;
  for (const Vector3& p : scan.points_W) {
    if (limited && ((p - scan.origin_W).squaredNorm() < min_range2 || (config_.min_z && p.z() < *config_.min_z) ||
                    (config_.max_z && p.z() > *config_.max_z))) {
      continue;
    }
    cloud.push_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
  }
  out.points = cloud.size();
  const octomap::point3d origin(static_cast<float>(scan.origin_W.x()), static_cast<float>(scan.origin_W.y()),
                                static_cast<float>(scan.origin_W.z()));
  // The tree OctoMap's own insertPointCloud builds (not discretized: a voxel crossed by many
  // rays gets their evidence), with the voxels it reclassified reported on the way.
  std::vector<KeyChange> changed;
  tree_.reportPointCloud(cloud, origin, max_range, changed);
  out.changes.reserve(changed.size());
  for (const KeyChange& c : changed) {
    out.changes.push_back({indexOf(c.key), c.occupied ? VoxelState::kOccupied : VoxelState::kFree});
  }
  sortByIndex(out.changes);
  out.accepted = true;
  return out;
}

VoxelState Mapper::classify(const VoxelIndex& index) const
{
  const auto key = grid_.octomapKey(index);
  if (!key) {
    return VoxelState::kUnknown;
  }
  const octomap::OcTreeNode* node = settled().search(octomap::OcTreeKey((*key)[0], (*key)[1], (*key)[2]));
  if (node == nullptr) {
    return VoxelState::kUnknown;
  }
  return tree_.isNodeOccupied(node) ? VoxelState::kOccupied : VoxelState::kFree;
}

std::vector<VoxelChange> classificationOf(const octomap::OcTree& tree)
{
  std::vector<VoxelChange> out;
  const unsigned max_depth = tree.getTreeDepth();
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    const VoxelState state = tree.isNodeOccupied(*it) ? VoxelState::kOccupied : VoxelState::kFree;
    const octomap::OcTreeKey key = it.getKey();
    // A pruned leaf at depth d stands for 2^(16−d) voxels per axis, from its aligned key.
    const unsigned span = 1U << (max_depth - it.getDepth());
    const octomap::key_type mask = static_cast<octomap::key_type>(~(span - 1U));
    for (unsigned dx = 0; dx < span; ++dx) {
      for (unsigned dy = 0; dy < span; ++dy) {
        for (unsigned dz = 0; dz < span; ++dz) {
          const octomap::OcTreeKey k(static_cast<octomap::key_type>((key[0] & mask) + dx),
                                     static_cast<octomap::key_type>((key[1] & mask) + dy),
                                     static_cast<octomap::key_type>((key[2] & mask) + dz));
          out.push_back({indexOf(k), state});
        }
      }
    }
  }
  sortByIndex(out);
  return out;
}

TreeImage Mapper::image(bool with_data) const
{
  if (const auto box = tree_.voxelBox(); box && !tree_.holdsNoVoxel()) {  // an empty map's is the empty tree's
    return boxImage(*box, with_data);
  }
  return treeImage(settled(), with_data);
}

std::shared_future<TreeImage> Mapper::imageLater(bool with_data, std::function<void()> done)
{
  awaitImage();  // the image before: its thread may still read the words
  auto box = tree_.voxelBox();
  if (!box) {
    std::promise<TreeImage> ready;
    ready.set_value(treeImage(settled(), with_data));
    if (done) {
      done();
    }
    return ready.get_future().share();
  }
  image_words_.assign(box->words, box->words + tree_.voxelCount());
  box->words = image_words_.data();
  tree_.takeChangedBlocks(image_changed_);
  image_job_ = std::async(std::launch::async, [this, box = *box, with_data, done = std::move(done)] {
                 TreeImage image = boxImage(box, with_data, &image_cache_, &image_changed_);
                 if (done) {
                   done();
                 }
                 return image;
               }).share();
  return image_job_;
}

std::vector<VoxelChange> Mapper::classification() const { return classificationOf(settled()); }

bool Mapper::save(const std::filesystem::path& file) const
{
  const std::vector<std::uint8_t> bytes = snapshot();
  std::ofstream out(file, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(out);
}

bool Mapper::readTree(std::istream& in)
{
  if (settled().size() != 0) {
    return false;
  }
  tree_.readData(in);
  if (!in) {
    tree_.clear();
  }
  tree_.resync();
  return static_cast<bool>(in);
}

std::optional<std::vector<VoxelChange>> classificationOf(const std::vector<std::uint8_t>& snapshot, double resolution)
{
  std::istringstream in(std::string(snapshot.begin(), snapshot.end()));
  octomap::OcTree tree(resolution);
  if (!tree.readBinary(in) || std::abs(tree.getResolution() - resolution) > 1e-9) {
    return std::nullopt;
  }
  return classificationOf(tree);
}

std::optional<std::vector<geometry::Vector3>> occupiedCentres(const std::vector<std::uint8_t>& snapshot,
                                                              double resolution)
{
  const auto voxels = classificationOf(snapshot, resolution);
  if (!voxels) {
    return std::nullopt;
  }
  const geometry::VoxelGrid grid(resolution);
  std::vector<geometry::Vector3> centres;
  for (const auto& v : *voxels) {
    if (v.state == VoxelState::kOccupied) {
      centres.push_back(grid.centre(v.index));
    }
  }
  return centres;
}

}  // namespace quad::mapping
