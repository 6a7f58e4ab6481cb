// SPDX-License-Identifier: BSD-3-Clause
// The mapper's cost per scan beside a bare OcTree::insertPointCloud on the same clouds,
// resolution and range, and how far their classifications agree.
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <random>
#include <sstream>

#include "quad/common/yaml_input.hpp"
#include "quad/mapping/map_follower.hpp"
#include "quad/mapping/mapper.hpp"
#include "quad/mapping/tree_bytes.hpp"
#include "quad/plant/sensors.hpp"
#include "quad/world/world_file.hpp"

namespace {

using namespace quad;

/// The benchmark world: configs/worlds/forest.yaml.
const std::string kForest = quad::common::readTextFile(QUAD_CONFIG_DIR "/worlds/forest.yaml");
/// The demo mission's world: configs/worlds/demo.yaml.
const std::string kDemo = quad::common::readTextFile(QUAD_CONFIG_DIR "/worlds/demo.yaml");

struct Scans {
  std::vector<mapping::Scan> scans;
};

/// 100 scans of a 160x120 camera flying through the forest.
const Scans& scans()
{
  static const Scans s = [] {
    const world::World world = world::parseWorld(kForest, "forest");
    plant::DepthCameraConfig config;
    config.width = 160;
    config.height = 120;
    config.max_range = 20.0;
    const plant::DepthCamera camera(config);
    std::mt19937_64 rng(1);
    Scans out;
    for (int k = 0; k < 100; ++k) {
      const geometry::Pose3 body{geometry::Vector3(0.5 * k, 0.0, 2.0), geometry::fromAxisAngle(geometry::Vector3::UnitZ(), 0.02 * k)};
      const plant::DepthScan d = camera.capture(world, body, rng);
      mapping::Scan scan;
      scan.origin_W = d.sensor_W.p;
      scan.max_range = config.max_range;
      for (const auto& p : d.points_S) {
        scan.points_W.push_back(d.sensor_W.transform(p.cast<double>()));
      }
      out.scans.push_back(std::move(scan));
    }
    return out;
  }();
  return s;
}

/// The demo mission's clouds: its camera (64x48, 20 m) at 10 Hz along the straight line to
/// its goal at 2 m/s, 2 m up, turning a little from side to side.
const Scans& demoScans()
{
  static const Scans s = [] {
    const world::World world = world::parseWorld(kDemo, "demo");
    const plant::DepthCamera camera(plant::DepthCameraConfig{});
    std::mt19937_64 rng(1);
    Scans out;
    for (int k = 0; k < 250; ++k) {
      const geometry::Pose3 body{geometry::Vector3(0.2 * k, 0.0, 2.0),
                                 geometry::fromAxisAngle(geometry::Vector3::UnitZ(), 0.3 * std::sin(0.1 * k))};
      const plant::DepthScan d = camera.capture(world, body, rng);
      mapping::Scan scan;
      scan.origin_W = d.sensor_W.p;
      scan.max_range = camera.config().max_range;
      for (const auto& p : d.points_S) {
        scan.points_W.push_back(d.sensor_W.transform(p.cast<double>()));
      }
      out.scans.push_back(std::move(scan));
    }
    return out;
  }();
  return s;
}

octomap::Pointcloud cloudOf(const mapping::Scan& s)
{
  octomap::Pointcloud cloud;
  for (const auto& p : s.points_W) {
    cloud.push_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
  }
  return cloud;
}

// Each iteration maps the whole flight (100 scans) into a fresh tree, so both sides see the
// same sequence of tree states; items are scans.
void BM_Mapper_Integrate(benchmark::State& state)
{
  for (auto _ : state) {
    mapping::Mapper mapper(mapping::MapperConfig{});
    for (const auto& s : scans().scans) {
      benchmark::DoNotOptimize(mapper.integrate(s));
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(scans().scans.size()));
  state.counters["points_per_scan"] = static_cast<double>(scans().scans.front().points_W.size());
}

/// Maps a flight's scans into a map limited to its world's box (one voxel beyond), as the
/// mapping node limits its map to the flown world's: updates of voxels at their clamping
/// bound are dropped without a descent, and rays stop where they leave the box. Each scan's
/// changes, then the octree brought up to date (Mapper::settle) after every scan, as a
/// reader of the tree after every scan would have it; with `changes_only`, the time to the
/// changes alone (the settling untimed), the node's work for a scan. Items are scans.
void mapBoxed(benchmark::State& state, const std::string& world_text, const Scans& flight, bool changes_only = false)
{
  const world::World world = world::parseWorld(world_text, "world");
  mapping::MapperConfig config;
  config.coverWorld(world.bounds().min, world.bounds().max);
  for (auto _ : state) {
    mapping::Mapper mapper(config);
    for (const auto& s : flight.scans) {
      benchmark::DoNotOptimize(mapper.integrate(s));
      if (changes_only) {
        state.PauseTiming();
      }
      mapper.settle();
      if (changes_only) {
        state.ResumeTiming();
      }
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(flight.scans.size()));
}

// The forest flight in the forest's box.
void BM_Mapper_IntegrateBoxed(benchmark::State& state) { mapBoxed(state, kForest, scans()); }

// The demo's flight in the demo world's box: the whole work, and the time to the changes.
void BM_Mapper_DemoFlight(benchmark::State& state) { mapBoxed(state, kDemo, demoScans()); }
void BM_Mapper_DemoFlightChanges(benchmark::State& state) { mapBoxed(state, kDemo, demoScans(), true); }

/// The demo's flight in the demo world's box, with an image of the map (snapshot and
/// checkpoint) every 10 scans, as the mapping node takes one a second: made from the box's
/// voxels (`from_voxels`, on a copy of them, as Mapper::imageLater does), or the octree
/// brought up to date with the scans since the last and walked, as the node did before.
/// Only the images are timed; items are images.
void demoImages(benchmark::State& state, bool from_voxels)
{
  const world::World world = world::parseWorld(kDemo, "world");
  mapping::MapperConfig config;
  config.coverWorld(world.bounds().min, world.bounds().max);
  std::int64_t images = 0;
  for (auto _ : state) {
    state.PauseTiming();
    mapping::Mapper mapper(config);
    for (std::size_t k = 0; k < demoScans().scans.size(); ++k) {
      benchmark::DoNotOptimize(mapper.integrate(demoScans().scans[k]));
      if (k % 10 != 9) {
        continue;
      }
      state.ResumeTiming();
      if (from_voxels) {
        benchmark::DoNotOptimize(mapper.imageLater(true).get().nodes);
      } else {
        mapper.settle();
        benchmark::DoNotOptimize(mapping::treeImage(mapper.tree(), true).nodes);
      }
      state.PauseTiming();
      ++images;
    }
    state.ResumeTiming();
  }
  state.SetItemsProcessed(images);
}

void BM_DemoImages_FromVoxels(benchmark::State& state) { demoImages(state, true); }
void BM_DemoImages_SettledTree(benchmark::State& state) { demoImages(state, false); }

void BM_OcTree_InsertPointCloud(benchmark::State& state)
{
  std::vector<octomap::Pointcloud> clouds;
  for (const auto& s : scans().scans) {
    clouds.push_back(cloudOf(s));
  }
  for (auto _ : state) {
    octomap::OcTree tree(0.2);
    for (std::size_t k = 0; k < clouds.size(); ++k) {
      const auto& s = scans().scans[k];
      tree.insertPointCloud(clouds[k],
                            octomap::point3d(static_cast<float>(s.origin_W.x()), static_cast<float>(s.origin_W.y()),
                                             static_cast<float>(s.origin_W.z())),
                            20.0);
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(clouds.size()));
}

/// Agreement of the final classification after all scans, over the union of known voxels.
void BM_ClassificationAgreement(benchmark::State& state)
{
  mapping::Mapper mapper(mapping::MapperConfig{});
  octomap::OcTree tree(0.2);
  for (const auto& s : scans().scans) {
    mapper.integrate(s);
    tree.insertPointCloud(cloudOf(s),
                          octomap::point3d(static_cast<float>(s.origin_W.x()), static_cast<float>(s.origin_W.y()),
                                           static_cast<float>(s.origin_W.z())),
                          20.0);
  }
  std::map<std::tuple<int, int, int>, std::pair<int, int>> both;  // state + 1, 0 for unknown
  for (const auto& c : mapper.classification()) {
    both[{c.index.x(), c.index.y(), c.index.z()}].first = static_cast<int>(c.state);
  }
  for (const auto& c : mapping::classificationOf(tree)) {
    both[{c.index.x(), c.index.y(), c.index.z()}].second = static_cast<int>(c.state);
  }
  std::size_t same = 0;
  for (const auto& [index, states] : both) {
    same += states.first == states.second ? 1U : 0U;
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(same);
  }
  state.counters["voxels"] = static_cast<double>(both.size());
  state.counters["agreement_percent"] = 100.0 * static_cast<double>(same) / static_cast<double>(both.size());
}

/// The mapper after the whole flight.
const mapping::Mapper& flightMapper()
{
  static const mapping::Mapper mapper = [] {
    mapping::Mapper m(mapping::MapperConfig{});
    for (const auto& s : scans().scans) {
      m.integrate(s);
    }
    return m;
  }();
  return mapper;
}

/// The map after the whole flight, as the mapper's snapshot bytes.
const std::vector<std::uint8_t>& flightSnapshot()
{
  static const std::vector<std::uint8_t> bytes = flightMapper().snapshot();
  return bytes;
}

// The flight's tree in OctoMap's two byte formats (the snapshot's .bt, the checkpoint's node
// data): written straight into a buffer against OctoMap's stream writers, the same bytes;
// items are tree nodes.
template <class Write>
void writeTreeBench(benchmark::State& state, Write write)
{
  const octomap::OcTree& tree = flightMapper().tree();
  std::size_t bytes = 0;
  for (auto _ : state) {
    bytes = write(tree);
    benchmark::DoNotOptimize(bytes);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(tree.size()));
  state.counters["bytes"] = static_cast<double>(bytes);
}

void BM_Snapshot_TreeBytes(benchmark::State& state)
{
  writeTreeBench(state, [](const octomap::OcTree& t) { return mapping::binaryTreeBytes(t).size(); });
}

void BM_Snapshot_OctoMapStream(benchmark::State& state)
{
  writeTreeBench(state, [](const octomap::OcTree& t) {
    std::ostringstream out;
    t.writeBinaryConst(out);
    return out.str().size();
  });
}

void BM_TreeData_TreeBytes(benchmark::State& state)
{
  writeTreeBench(state, [](const octomap::OcTree& t) { return mapping::treeDataBytes(t).size(); });
}

void BM_TreeData_OctoMapStream(benchmark::State& state)
{
  writeTreeBench(state, [](const octomap::OcTree& t) {
    std::ostringstream out;
    t.writeData(out);
    return out.str().size();
  });
}

// What the running mapper writes with each periodic snapshot: the .bt, the checkpoint's node
// data and the map's memory use; from one walk, against a walk each (OctoMap's own
// memoryUsage() counting the leaves).
void BM_SnapshotWithCheckpoint_OneWalk(benchmark::State& state)
{
  writeTreeBench(state, [](const octomap::OcTree& t) {
    const mapping::TreeImage image = mapping::treeImage(t, true);
    return image.binary.size() + image.data.size() + image.memory_bytes;
  });
}

void BM_SnapshotWithCheckpoint_WalkEach(benchmark::State& state)
{
  writeTreeBench(state, [](const octomap::OcTree& t) {
    return mapping::binaryTreeBytes(t).size() + mapping::treeDataBytes(t).size() + t.memoryUsage();
  });
}

// A planner joining (or started again): from nothing to the snapshot's map; items are voxels.
void BM_MapFollower_Join(benchmark::State& state)
{
  flightSnapshot();  // built before the timing
  std::size_t voxels = 0;
  for (auto _ : state) {
    mapping::MapFollower follower(0.2);
    voxels = follower.snapshot(100, flightSnapshot())->size();
    benchmark::DoNotOptimize(voxels);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(voxels));
  state.counters["voxels"] = static_cast<double>(voxels);
}

// A planner holding the map that missed an update: the next snapshot fills the gap (the
// change it brings is small, the comparison is of the whole map); items are voxels.
void BM_MapFollower_FillGap(benchmark::State& state)
{
  mapping::MapFollower follower(0.2);
  const std::size_t voxels = follower.snapshot(100, flightSnapshot())->size();
  std::uint64_t seq = 100;
  for (auto _ : state) {
    follower.update(seq + 2, {});  // seq + 1 missed
    benchmark::DoNotOptimize(follower.snapshot(seq + 2, flightSnapshot()));
    seq += 2;
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(voxels));
  state.counters["voxels"] = static_cast<double>(voxels);
}

BENCHMARK(BM_Mapper_Integrate)->Unit(benchmark::kMillisecond)->MinTime(5.0);
BENCHMARK(BM_Mapper_IntegrateBoxed)->Unit(benchmark::kMillisecond)->MinTime(5.0);
BENCHMARK(BM_Mapper_DemoFlight)->Unit(benchmark::kMillisecond)->MinTime(5.0);
BENCHMARK(BM_Mapper_DemoFlightChanges)->Unit(benchmark::kMillisecond)->MinTime(5.0);
BENCHMARK(BM_DemoImages_FromVoxels)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DemoImages_SettledTree)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OcTree_InsertPointCloud)->Unit(benchmark::kMillisecond)->MinTime(5.0);
BENCHMARK(BM_ClassificationAgreement)->Iterations(1);
BENCHMARK(BM_MapFollower_Join)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MapFollower_FillGap)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Snapshot_TreeBytes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Snapshot_OctoMapStream)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TreeData_TreeBytes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TreeData_OctoMapStream)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SnapshotWithCheckpoint_OneWalk)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SnapshotWithCheckpoint_WalkEach)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
