// The same scripted navigation through unknown terrain, replanned by D* Lite and by A* from
// scratch at every step (same graph, heap and tie-breaking): expansions, heap pushes, time.
#include <benchmark/benchmark.h>

#include <chrono>
#include <queue>
#include <random>
#include <set>

#include "quad/planning/dstar_lite.hpp"

namespace {

using namespace quad::planning;
using quad::geometry::VoxelGrid;

constexpr int kN = 100;  // 100 x 100 x 100 = 1,000,000 cells
constexpr int kSensorRadius = 6;
constexpr int kSteps = 40;

/// The hidden world: vertical pillars and floating blocks, seeded.
std::set<std::tuple<int, int, int>> world()
{
  std::set<std::tuple<int, int, int>> occupied;
  std::mt19937_64 rng(42);
  std::uniform_int_distribution<int> u(0, kN - 1);
  for (int k = 0; k < 900; ++k) {  // pillars, 2x2 cells, full height
    const int x = u(rng), y = u(rng);
    for (int z = 0; z < kN; ++z) {
      for (int dx = 0; dx < 2; ++dx) {
        for (int dy = 0; dy < 2; ++dy) {
          occupied.insert({std::min(kN - 1, x + dx), std::min(kN - 1, y + dy), z});
        }
      }
    }
  }
  return occupied;
}

struct AStarResult {
  double cost = kInfinity;
  std::uint64_t expansions = 0;
  std::uint64_t pushes = 0;
  std::vector<Cell> path;
};

/// A* from scratch on the planner's graph, the same priority order as D* Lite's queue.
AStarResult aStar(const DStarLite& graph, Cell start, Cell goal)
{
  AStarResult out;
  using Item = std::tuple<double, double, Cell>;  // f, g, cell: ties by g, then cell
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  std::unordered_map<Cell, double> g{{start, 0.0}};
  std::unordered_map<Cell, Cell> parent;
  open.push({graph.heuristic(start, goal), 0.0, start});
  ++out.pushes;
  std::vector<std::pair<Cell, double>> around;
  while (!open.empty()) {
    const auto [f, gu, u] = open.top();
    open.pop();
    if (gu > g[u]) {
      continue;
    }
    ++out.expansions;
    if (u == goal) {
      out.cost = gu;
      for (Cell c = goal; c != start; c = parent[c]) {
        out.path.push_back(c);
      }
      out.path.push_back(start);
      std::reverse(out.path.begin(), out.path.end());
      return out;
    }
    graph.neighbours(u, around);
    for (const auto& [v, step] : around) {
      const double c = graph.edgeCost(u, v);
      if (c == kInfinity) {
        continue;
      }
      const auto it = g.find(v);
      if (it == g.end() || gu + c < it->second) {
        g[v] = gu + c;
        parent[v] = u;
        open.push({gu + c + graph.heuristic(v, goal), gu + c, v});
        ++out.pushes;
      }
    }
  }
  return out;
}

/// Reveals the hidden obstacles within the sensor radius of the robot.
void sense(DStarLite& planner, const std::set<std::tuple<int, int, int>>& hidden, const VoxelIndex& at,
           std::set<std::tuple<int, int, int>>& known)
{
  for (int dz = -kSensorRadius; dz <= kSensorRadius; ++dz) {
    for (int dy = -kSensorRadius; dy <= kSensorRadius; ++dy) {
      for (int dx = -kSensorRadius; dx <= kSensorRadius; ++dx) {
        const std::tuple<int, int, int> v{at.x() + dx, at.y() + dy, at.z() + dz};
        if (hidden.contains(v) && known.insert(v).second) {
          planner.updateVoxel(VoxelIndex(std::get<0>(v), std::get<1>(v), std::get<2>(v)), Occupancy::kOccupied);
        }
      }
    }
  }
}

void navigate(benchmark::State& state, bool incremental)
{
  static const auto hidden = world();
  double cost_sum = 0.0;
  std::uint64_t expansions = 0, pushes = 0, replans = 0;
  for (auto _ : state) {
    DStarLite planner(Lattice(VoxelGrid(1.0), Vector3(0, 0, 0), Vector3(kN, kN, kN)), {26, true, 0.0});
    std::set<std::tuple<int, int, int>> known;
    VoxelIndex robot(1, 1, 50);
    const Cell goal = *planner.lattice().cell(VoxelIndex(kN - 2, kN - 2, 50));
    planner.setGoal(goal);
    for (int step = 0; step < kSteps; ++step) {
      sense(planner, hidden, robot, known);
      const Cell start = *planner.lattice().cell(robot);
      std::vector<Cell> path;
      if (incremental) {
        planner.setStart(start);
        const PlanResult r = planner.plan();
        expansions += r.expansions;
        pushes += r.heap_pushes;
        cost_sum += r.cost;
        path = r.cells;
      } else {
        const AStarResult r = aStar(planner, start, goal);
        expansions += r.expansions;
        pushes += r.pushes;
        cost_sum += r.cost;
        path = r.path;
      }
      ++replans;
      if (path.size() < 3) {
        break;
      }
      robot = planner.lattice().voxel(path[2]);  // two cells per step
    }
  }
  state.counters["expansions_per_replan"] = static_cast<double>(expansions) / static_cast<double>(replans);
  state.counters["pushes_per_replan"] = static_cast<double>(pushes) / static_cast<double>(replans);
  state.counters["cost_sum"] = cost_sum / static_cast<double>(state.iterations());
  state.counters["replans"] = static_cast<double>(replans) / static_cast<double>(state.iterations());
}

void BM_Navigation_DStarLite(benchmark::State& state) { navigate(state, true); }
void BM_Navigation_RepeatedAStar(benchmark::State& state) { navigate(state, false); }

BENCHMARK(BM_Navigation_DStarLite)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_Navigation_RepeatedAStar)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
