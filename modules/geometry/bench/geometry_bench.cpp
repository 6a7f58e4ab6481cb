// SPDX-License-Identifier: BSD-3-Clause
// quad::geometry's hot paths, each beside Eigen's implementation of the same operation.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include "quad/geometry/distance.hpp"
#include "quad/geometry/grid.hpp"
#include "quad/geometry/haar.hpp"

namespace {

using namespace quad::geometry;

const std::vector<Quaternion>& rotations()
{
  static const auto qs = uniformRotations(1024, 1);
  return qs;
}

void BM_QuatToMatrix_Quad(benchmark::State& state)
{
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(toMatrix(rotations()[i++ & 1023]));
  }
}

void BM_QuatToMatrix_Eigen(benchmark::State& state)
{
  std::size_t i = 0;
  for (auto _ : state) {
    const Quaternion& q = rotations()[i++ & 1023];
    benchmark::DoNotOptimize(Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix());
  }
}

void BM_MatrixToQuat_Quad(benchmark::State& state)
{
  std::vector<Matrix3> ms;
  for (const auto& q : rotations()) {
    ms.push_back(toMatrix(q));
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(fromMatrix(ms[i++ & 1023]));
  }
}

void BM_MatrixToQuat_Eigen(benchmark::State& state)
{
  std::vector<Matrix3> ms;
  for (const auto& q : rotations()) {
    ms.push_back(toMatrix(q));
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(Eigen::Quaterniond(ms[i++ & 1023]));
  }
}

void BM_Rho(benchmark::State& state)
{
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(rho(rotations()[i & 1023], rotations()[(i + 1) & 1023]));
    ++i;
  }
}

void BM_GeodesicAngle_Quaternion(benchmark::State& state)
{
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(geodesicAngle(rotations()[i & 1023], rotations()[(i + 1) & 1023]));
    ++i;
  }
}

void BM_GeodesicAngle_Eigen(benchmark::State& state)
{
  std::size_t i = 0;
  for (auto _ : state) {
    const Quaternion& a = rotations()[i & 1023];
    const Quaternion& b = rotations()[(i + 1) & 1023];
    benchmark::DoNotOptimize(Eigen::Quaterniond(a.w, a.x, a.y, a.z)
                                 .angularDistance(Eigen::Quaterniond(b.w, b.x, b.y, b.z)));
    ++i;
  }
}

void BM_Frobenius(benchmark::State& state)
{
  const Matrix3 a = toMatrix(rotations()[0]);
  const Matrix3 b = toMatrix(rotations()[1]);
  for (auto _ : state) {
    benchmark::DoNotOptimize(frobeniusDistance(a, b));
  }
}

void BM_HaarSample(benchmark::State& state)
{
  std::mt19937_64 rng(1);
  for (auto _ : state) {
    benchmark::DoNotOptimize(uniformRotation(rng));
  }
}

void BM_WorldToLatticeCell(benchmark::State& state)
{
  const Lattice lattice(VoxelGrid(0.2), Vector3(-5, -10, 0), Vector3(60, 10, 10));
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vector3> points;
  for (int k = 0; k < 1024; ++k) {
    points.emplace_back(-5 + 65 * u(rng), -10 + 20 * u(rng), 10 * u(rng));
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(lattice.cellAt(points[i++ & 1023]));
  }
}

void BM_LatticeCellToCentre(benchmark::State& state)
{
  const Lattice lattice(VoxelGrid(0.2), Vector3(-5, -10, 0), Vector3(60, 10, 10));
  std::int64_t c = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(lattice.centre(c));
    c = (c + 7919) % lattice.size();
  }
}

BENCHMARK(BM_QuatToMatrix_Quad);
BENCHMARK(BM_QuatToMatrix_Eigen);
BENCHMARK(BM_MatrixToQuat_Quad);
BENCHMARK(BM_MatrixToQuat_Eigen);
BENCHMARK(BM_Rho);
BENCHMARK(BM_GeodesicAngle_Quaternion);
BENCHMARK(BM_GeodesicAngle_Eigen);
BENCHMARK(BM_Frobenius);
BENCHMARK(BM_HaarSample);
BENCHMARK(BM_WorldToLatticeCell);
BENCHMARK(BM_LatticeCellToCentre);

}  // namespace

BENCHMARK_MAIN();
