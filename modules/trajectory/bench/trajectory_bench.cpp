// SPDX-License-Identifier: BSD-3-Clause
// The generator's cost for the paths the controller hands it: a receding horizon of known-free
// path with a few corners, at the forest's speeds; and a stop along a trajectory at speed.
#include <benchmark/benchmark.h>

#include <random>

#include "quad/trajectory/generator.hpp"

namespace {

using quad::trajectory::GenerateStatus;
using quad::trajectory::Generator;
using quad::trajectory::GeneratorConfig;
using quad::trajectory::State;
using quad::trajectory::Vector3;

GeneratorConfig config(double speed)
{
  GeneratorConfig c;
  c.limits.max_speed = speed;
  c.limits.max_acceleration = 6.0;
  c.limits.max_jerk = 30.0;
  c.limits.max_thrust = 16.0;
  c.limits.min_thrust = 4.0;
  c.corridor = 0.25;
  c.corner_deviation = 0.15;
  return c;
}

/// A path of `corners` corners over about `length` m, zig-zagging as a forest path does.
std::vector<Vector3> forestPath(int corners, double length, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> sideways(-1.5, 1.5);
  std::vector<Vector3> path{Vector3(0, 0, 2)};
  for (int i = 1; i <= corners + 1; ++i) {
    path.emplace_back(length * i / (corners + 1), i == corners + 1 ? 0.0 : sideways(rng), 2.0);
  }
  return path;
}

void BM_GenerateFromRest(benchmark::State& state)
{
  const Generator generator(config(static_cast<double>(state.range(0))));
  const auto path = forestPath(static_cast<int>(state.range(1)), 20.0, 7);
  int iterations = 0;
  for (auto _ : state) {
    const auto r = generator.generate(0.0, State{path.front()}, path);
    iterations = r.iterations;
    benchmark::DoNotOptimize(r);
  }
  state.counters["solves"] = iterations;
}
BENCHMARK(BM_GenerateFromRest)->Args({3, 2})->Args({7, 2})->Args({10, 2})->Args({10, 5})->Unit(benchmark::kMicrosecond);

void BM_GenerateAtSpeed(benchmark::State& state)
{
  // A replan at cruise: from 8 m/s along x onto a new 20 m path.
  const Generator generator(config(10.0));
  const auto path = forestPath(static_cast<int>(state.range(0)), 20.0, 9);
  const State s{path.front(), Vector3(8.0, 0.0, 0.0)};
  int iterations = 0;
  bool ok = false;
  for (auto _ : state) {
    const auto r = generator.generate(0.0, s, path);
    iterations = r.iterations;
    ok = r.status == GenerateStatus::kOk;
    benchmark::DoNotOptimize(r);
  }
  state.counters["solves"] = iterations;
  state.counters["ok"] = ok ? 1 : 0;
}
BENCHMARK(BM_GenerateAtSpeed)->Arg(2)->Arg(5)->Unit(benchmark::kMicrosecond);

void BM_Stop(benchmark::State& state)
{
  const Generator generator(config(10.0));
  const auto path = forestPath(3, 40.0, 11);
  const auto flown = generator.generate(0.0, State{path.front()}, path).trajectory;
  const double t = 0.5 * flown.endTime();
  for (auto _ : state) {
    benchmark::DoNotOptimize(generator.stop(flown, t));
  }
}
BENCHMARK(BM_Stop)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
