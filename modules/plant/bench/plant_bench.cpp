// SPDX-License-Identifier: BSD-3-Clause
// The plant's costs: RK4 physics steps, depth frames in a 1,000-obstacle forest (indexed ray
// casting beside brute force) and in a real scanned office (voxels marched at 0.32 to 0.04 m,
// in 1 to 16 copies of the floor, and beside the same scan as one box per run of voxels),
// world generation, and a second of sim time of fleets of 1 to 16 vehicles.
#include <benchmark/benchmark.h>

#include "quad/common/yaml_input.hpp"
#include "quad/plant/fleet.hpp"
#include "quad/plant/sensors.hpp"
#include "quad/plant/simulation.hpp"
#include "quad/world/scan_file.hpp"
#include "quad/world/world_file.hpp"

namespace {

using namespace quad::plant;
namespace world = quad::world;

/// The benchmark world: configs/worlds/forest.yaml.
const std::string kForest = quad::common::readTextFile(QUAD_CONFIG_DIR "/worlds/forest.yaml");

void BM_PhysicsStep(benchmark::State& state)
{
  quad::vehicle::VehicleParams v;
  const QuadrotorDynamics dyn(v);
  RigidBodyState s;
  s.p_W.z() = 1e6;  // far from the ground for the whole run
  s.w_B = {0.1, 0.2, 0.3};
  const double w = v.hoverRotorSpeed(9.81);
  const RotorArray cmd{w, w * 1.01, w, w * 0.99};
  const Environment env;
  for (auto _ : state) {
    dyn.step(s, cmd, env, 1e-3);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_SimulationStepNoSensors(benchmark::State& state)
{
  SimulationConfig config;
  config.state_rate_hz = 0;
  config.imu.rate_hz = 0;
  config.depth.rate_hz = 0;
  Simulation sim({}, world::parseWorld(kForest, "forest"), config);
  quad::plant::RigidBodyState s;
  s.p_W = {0, 0, 2};
  sim.setState(s);
  const double w = sim.dynamics().params().hoverRotorSpeed(9.81);
  for (auto _ : state) {
    sim.commands().submit({w, w, w, w}, true, sim.timeNs(), sim.timeNs());
    benchmark::DoNotOptimize(sim.step());
  }
  state.SetItemsProcessed(state.iterations());
}

template <bool kBruteForce>
void depthFrame(benchmark::State& state)
{
  const world::World world = world::parseWorld(kForest, "forest");
  DepthCameraConfig config;
  config.width = 64;
  config.height = 48;
  config.max_range = 20.0;
  const DepthCamera camera(config);
  const quad::geometry::Pose3 body{quad::geometry::Vector3(0, 0, 2), {}};
  std::mt19937_64 rng(1);
  const auto pose = camera.sensorPose(body);
  const auto R = quad::geometry::toMatrix(pose.q);
  for (auto _ : state) {
    if constexpr (kBruteForce) {
      int hits = 0;
      for (const auto& d : camera.directions_S()) {
        hits += world.raycastBruteForce(pose.p, R * d, config.max_range) ? 1 : 0;
      }
      benchmark::DoNotOptimize(hits);
    } else {
      benchmark::DoNotOptimize(camera.capture(world, body, rng));
    }
  }
  state.counters["obstacles"] = static_cast<double>(world.obstacles().size());
  state.SetItemsProcessed(state.iterations());
}

void BM_DepthFrame64x48_Indexed(benchmark::State& state) { depthFrame<false>(state); }
void BM_DepthFrame64x48_BruteForce(benchmark::State& state) { depthFrame<true>(state); }

/// The scanned office floor (configs/worlds/scans/geb079.bt) voxelised at `resolution` [m].
world::VoxelMap office(double resolution)
{
  world::ScanPlacement at;
  at.resolution = resolution;
  return world::loadScan(QUAD_CONFIG_DIR "/worlds/scans/geb079.bt", at);
}

/// A world of the scan's box, from the corridor's start to its end: the scan itself as its
/// map (`solid`), or only `obstacles` in its box.
world::World corridorWorld(world::VoxelMap scan, std::vector<world::Obstacle> obstacles, bool solid)
{
  Vector3 lo, hi;
  scan.bounds(lo, hi);
  std::vector<world::VoxelMap> maps;
  if (solid) {
    maps.push_back(std::move(scan));
  }
  return world::World({lo, hi}, {2, -0.1, 0}, {26, -0.1, 1}, std::move(obstacles), 0.0, std::move(maps));
}

/// A 64x48 depth frame, 8 m range, from the corridor 1 m up looking down its length: the
/// indoor mission's camera.
void scanFrame(benchmark::State& state, const world::World& world)
{
  DepthCameraConfig config;
  config.width = 64;
  config.height = 48;
  config.max_range = 8.0;
  const DepthCamera camera(config);
  const quad::geometry::Pose3 body{quad::geometry::Vector3(2, -0.1, 1), {}};
  std::mt19937_64 rng(1);
  for (auto _ : state) {
    benchmark::DoNotOptimize(camera.capture(world, body, rng));
  }
  state.SetItemsProcessed(state.iterations() * config.width * config.height);  // rays
}

/// Rays per second against the voxel count: the same building at 0.32, 0.16, 0.08 (its own)
/// and 0.04 m, each step 8 times the voxels.
void BM_ScanDepthFrame_Voxels(benchmark::State& state)
{
  world::VoxelMap map = office(static_cast<double>(state.range(0)) / 1000.0);
  state.counters["voxels"] = static_cast<double>(map.occupiedVoxels().size());
  scanFrame(state, corridorWorld(std::move(map), {}, true));
}

/// Rays per second against the size of the map at one resolution: 1, 4 and 16 copies of the
/// floor side by side (16 m apart in y), the camera in the first.
void BM_ScanDepthFrame_Copies(benchmark::State& state)
{
  const world::VoxelMap floor = office(0.08);
  std::vector<world::VoxelIndex> voxels;
  for (int k = 0; k < state.range(0); ++k) {
    for (const auto& v : floor.occupiedVoxels()) {
      voxels.push_back(v + world::VoxelIndex(0, 200 * k, 0));  // 200 voxels: 16 m
    }
  }
  world::VoxelMap map("copies", floor.grid(), std::move(voxels));
  state.counters["voxels"] = static_cast<double>(map.occupiedVoxels().size());
  scanFrame(state, corridorWorld(std::move(map), {}, true));
}

/// The same scan at 0.08 m as boxes, one per run of occupied voxels along x, in the x-y grid
/// index of primitives: how a scan had to be given before voxel maps.
void BM_ScanDepthFrame_AsBoxes(benchmark::State& state)
{
  const world::VoxelMap map = office(0.08);
  std::vector<world::Obstacle> boxes;
  const auto& v = map.occupiedVoxels();  // sorted by z, y, then x: runs are consecutive
  for (std::size_t i = 0; i < v.size();) {
    std::size_t j = i + 1;
    while (j < v.size() && v[j].z() == v[i].z() && v[j].y() == v[i].y() && v[j].x() == v[j - 1].x() + 1) {
      ++j;
    }
    const Vector3 lo = v[i].cast<double>() * 0.08;
    const Vector3 size(0.08 * static_cast<double>(j - i), 0.08, 0.08);
    boxes.push_back(world::Obstacle::makeBox({lo + size / 2.0, size, 0.0}));
    i = j;
  }
  state.counters["boxes"] = static_cast<double>(boxes.size());
  scanFrame(state, corridorWorld(map, std::move(boxes), false));
}

void BM_WorldGeneration1000Trees(benchmark::State& state)
{
  for (auto _ : state) {
    benchmark::DoNotOptimize(world::parseWorld(kForest, "forest"));
  }
}

/// One second of sim time (1,000 steps) of a fleet of N vehicles in the forest, every sensor
/// at its default rate (state and IMU 250 Hz, a 64x48 depth frame at 10 Hz): the plant's cost
/// per vehicle, and what the others add to each camera (its rays are cast at them too). The
/// vehicles start 1 m apart, 2 m up, and fall (no commands): the cost does not depend on it.
void BM_FleetSecondOfSimTime(benchmark::State& state)
{
  const auto n = static_cast<std::uint32_t>(state.range(0));
  const world::World world = world::parseWorld(kForest, "forest");
  for (auto _ : state) {
    state.PauseTiming();
    std::vector<FleetVehicle> vehicles;
    for (std::uint32_t i = 0; i < n; ++i) {
      vehicles.push_back({i + 1, {}, world.start() + Vector3(0.0, 1.0 * i, 2.0), world.goal(), {}});
    }
    Fleet fleet(std::move(vehicles), world, SimulationConfig{});
    state.ResumeTiming();
    for (int k = 0; k < 1000; ++k) {
      benchmark::DoNotOptimize(fleet.step());
    }
  }
  state.counters["vehicles"] = n;
}

BENCHMARK(BM_PhysicsStep);
BENCHMARK(BM_SimulationStepNoSensors);
BENCHMARK(BM_DepthFrame64x48_Indexed)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DepthFrame64x48_BruteForce)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ScanDepthFrame_Voxels)->Arg(320)->Arg(160)->Arg(80)->Arg(40)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ScanDepthFrame_Copies)->Arg(1)->Arg(4)->Arg(16)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ScanDepthFrame_AsBoxes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WorldGeneration1000Trees)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FleetSecondOfSimTime)->Arg(1)->Arg(2)->Arg(4)->Arg(8)->Arg(16)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
