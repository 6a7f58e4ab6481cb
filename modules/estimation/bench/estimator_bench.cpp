// SPDX-License-Identifier: BSD-3-Clause
// One prediction (an IMU sample) and one update of each kind, for the filter on MRPT's SO(3)
// and the same filter on Eigen alone, side by side in one run.
#include <benchmark/benchmark.h>

#include <random>

#include "quad/estimation/error_state_filter.hpp"

namespace {

using namespace quad;
using estimation::Vector3;

/// A filter aligned at rest and run for a second, so every update finds it settled.
template <class Filter>
Filter settled()
{
  Filter f(estimation::EstimatorParams{});
  std::int64_t t = 0;
  for (int k = 0; k < 250; ++k) {
    t += 4'000'000;
    f.imu(t, Vector3(0.0, 0.0, 9.81), Vector3::Zero());
    if (k % 25 == 0) {
      f.position(t, Vector3(0.0, 0.0, 0.0), 0.02);
      f.baro(t, 0.0, 0.1);
    }
    if (k % 5 == 0) {
      f.mag(t, Vector3(0.0, 21.0, -43.0), 0.3);
    }
  }
  return f;
}

template <class Filter>
void BM_Predict(benchmark::State& state)
{
  Filter f = settled<Filter>();
  std::int64_t t = 1'000'000'000;
  for (auto _ : state) {
    t += 4'000'000;
    benchmark::DoNotOptimize(f.imu(t, Vector3(0.01, -0.02, 9.81), Vector3(0.001, 0.002, -0.001)));
  }
}

template <class Filter>
void BM_UpdatePosition(benchmark::State& state)
{
  Filter f = settled<Filter>();
  const std::int64_t t = f.estimate(0).t_ns;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f.position(t, Vector3(0.001, -0.001, 0.0), 0.02));
  }
}

template <class Filter>
void BM_UpdateBaro(benchmark::State& state)
{
  Filter f = settled<Filter>();
  const std::int64_t t = f.estimate(0).t_ns;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f.baro(t, 0.01, 0.1));
  }
}

template <class Filter>
void BM_UpdateMag(benchmark::State& state)
{
  Filter f = settled<Filter>();
  const std::int64_t t = f.estimate(0).t_ns;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f.mag(t, Vector3(0.1, 21.0, -43.0), 0.3));
  }
}

using Mrpt = estimation::BasicErrorStateFilter<estimation::MrptRotations>;
using Eigen = estimation::BasicErrorStateFilter<estimation::EigenRotations>;

BENCHMARK_TEMPLATE(BM_Predict, Mrpt);
BENCHMARK_TEMPLATE(BM_Predict, Eigen);
BENCHMARK_TEMPLATE(BM_UpdatePosition, Mrpt);
BENCHMARK_TEMPLATE(BM_UpdatePosition, Eigen);
BENCHMARK_TEMPLATE(BM_UpdateBaro, Mrpt);
BENCHMARK_TEMPLATE(BM_UpdateBaro, Eigen);
BENCHMARK_TEMPLATE(BM_UpdateMag, Mrpt);
BENCHMARK_TEMPLATE(BM_UpdateMag, Eigen);

}  // namespace

BENCHMARK_MAIN();
