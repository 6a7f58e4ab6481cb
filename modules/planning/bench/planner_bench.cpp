// SPDX-License-Identifier: BSD-3-Clause
// The same scripted navigation through unknown terrain replanned by D* Lite and by A* from
// scratch (same graph, heap and tie-breaking), side by side in one run: the robot follows
// D* Lite's path, and at every step both planners solve the same graph, so that their
// expansions, heap pushes and times compare replan for replan and their costs must agree.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <utility>

#include "quad/planning/dstar_lite.hpp"
#include "quad/planning/bucket_queue.hpp"

namespace {

using namespace quad::planning;
using quad::geometry::VoxelGrid;

constexpr int kN = 100;  // 100 x 100 x 100 = 1,000,000 cells
constexpr int kSensorRadius = 6;
constexpr int kMaxSteps = 2000;

/// The hidden world, one flag a cell (x fastest, as the lattice numbers cells).
struct World {
  std::vector<std::uint8_t> occupied = std::vector<std::uint8_t>(std::size_t{kN} * kN * kN, 0);
  void set(int x, int y, int z)
  {
    if (x >= 0 && y >= 0 && z >= 0 && x < kN && y < kN && z < kN) {
      occupied[static_cast<std::size_t>(x + kN * (y + kN * z))] = 1;
    }
  }
  bool at(int x, int y, int z) const { return occupied[static_cast<std::size_t>(x + kN * (y + kN * z))] != 0; }
};

/// A forest: 900 vertical 2x2 pillars, full height, seeded. Open: paths bend little.
World forest()
{
  World w;
  std::mt19937_64 rng(42);
  std::uniform_int_distribution<int> u(0, kN - 1);
  for (int k = 0; k < 900; ++k) {
    const int x = u(rng), y = u(rng);
    for (int z = 0; z < kN; ++z) {
      for (int d = 0; d < 4; ++d) {
        w.set(std::min(kN - 1, x + d % 2), std::min(kN - 1, y + d / 2), z);
      }
    }
  }
  return w;
}

/// Facades: five walls across the way (x = 15, 30, ... 75, two cells thick, wall to wall
/// and floor to ceiling), each with four 10x10 windows at seeded places. A window has to be
/// found by looking along the wall, and the known part of a wall bends every path.
World facades()
{
  World w;
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> u(0, kN - 10);
  for (int x0 = 15; x0 < kN - 20; x0 += 15) {
    std::vector<std::pair<int, int>> windows;
    for (int k = 0; k < 4; ++k) {
      windows.emplace_back(u(rng), u(rng));
    }
    for (int z = 0; z < kN; ++z) {
      for (int y = 0; y < kN; ++y) {
        const bool open = std::any_of(windows.begin(), windows.end(), [&](const auto& o) {
          return y >= o.first && y < o.first + 10 && z >= o.second && z < o.second + 10;
        });
        if (!open) {
          w.set(x0, y, z);
          w.set(x0 + 1, y, z);
        }
      }
    }
  }
  return w;
}

/// Overhangs: four walls across the way (x = 20, 40, 60, 80, two cells thick, wall to wall and
/// floor to ceiling), each with one 12x12 window, low (z 4-15) and high (z 84-95) in turn, at
/// seeded places along y; behind each low window a roof (z 20-21, ten cells deep, wall to
/// wall) overhangs the way. From mid-height the robot dips under, flies under the roof, climbs
/// to the next window: vertical detours of some 40 cells each, found as the walls come into view.
World overhangs()
{
  World w;
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> u(5, kN - 17);
  bool low = true;
  for (int x0 = 20; x0 < kN - 10; x0 += 20, low = !low) {
    const int wy = u(rng);
    const int wz = low ? 4 : 84;
    for (int z = 0; z < kN; ++z) {
      for (int y = 0; y < kN; ++y) {
        if (y >= wy && y < wy + 12 && z >= wz && z < wz + 12) {
          continue;
        }
        w.set(x0, y, z);
        w.set(x0 + 1, y, z);
      }
    }
    if (low) {
      for (int x = x0 + 2; x < x0 + 12; ++x) {
        for (int y = 0; y < kN; ++y) {
          w.set(x, y, 20);
          w.set(x, y, 21);
        }
      }
    }
  }
  return w;
}

struct AStarResult {
  double cost = kInfinity;
  std::uint64_t expansions = 0;
  std::uint64_t pushes = 0;
  std::vector<Cell> path;
};

/// A* from scratch on the planner's graph, in the same queue as D* Lite's (BucketQueue: each
/// cell once, its key lowered in place, buckets one cell wide) with the same order: f, then g, then cell number. Its g
/// and parent live in flat arrays over the lattice, reset in O(1) by a search number, so that
/// neither side pays for hashing the other does not.
class AStar {
public:
  explicit AStar(const DStarLite& graph)
      : graph_(graph),
        g_(static_cast<std::size_t>(graph.lattice().size())),
        parent_(g_.size()),
        search_(g_.size(), 0),
        places_(g_.size()),
        open_(Place{places_.data()}, Level{1.0 / graph.lattice().grid().resolution()})
  {
  }

  AStarResult plan(Cell start, Cell goal)
  {
    ++number_;
    const Eigen::Vector3i to = graph_.coordinates(goal);
    const auto heuristic = [&](Cell c) { return graph_.distance(graph_.coordinates(c), to); };
    AStarResult out;
    set(start, 0.0, start);
    open_.set(start, {heuristic(start), 0.0});
    ++out.pushes;
    std::vector<std::pair<Cell, double>> around;
    while (!open_.empty()) {
      const Cell u = open_.top().cell;
      const double gu = open_.top().key.g;
      open_.pop();
      ++out.expansions;
      if (u == goal) {
        out.cost = gu;
        for (Cell c = goal; c != start; c = parent_[static_cast<std::size_t>(c)]) {
          out.path.push_back(c);
        }
        out.path.push_back(start);
        std::reverse(out.path.begin(), out.path.end());
        break;
      }
      graph_.neighbours(u, around);
      for (const auto& [v, step] : around) {
        // u is traversable (it was reached), so the edge costs its step when v is too.
        if (!graph_.traversable(v) || !(gu + step < g(v))) {
          continue;
        }
        set(v, gu + step, u);
        open_.set(v, {gu + step + heuristic(v), gu + step});
        ++out.pushes;
      }
    }
    open_.clear();
    return out;
  }

private:
  struct Key {
    double f;
    double g;
    auto operator<=>(const Key&) const = default;  // f, then g
  };
  struct Place {
    QueuePlace* places;
    QueuePlace& operator()(Cell c) const { return places[static_cast<std::size_t>(c)]; }
  };
  struct Level {
    double per_metre;
    std::uint32_t operator()(const Key& k) const { return static_cast<std::uint32_t>(k.f * per_metre + 0.38196601125); }
  };

  double g(Cell c) const
  {
    const auto i = static_cast<std::size_t>(c);
    return search_[i] == number_ ? g_[i] : kInfinity;
  }
  void set(Cell c, double g, Cell parent)
  {
    const auto i = static_cast<std::size_t>(c);
    search_[i] = number_;
    g_[i] = g;
    parent_[i] = parent;
  }

  const DStarLite& graph_;
  std::vector<double> g_;
  std::vector<Cell> parent_;
  std::vector<std::uint32_t> search_;
  std::vector<QueuePlace> places_;
  BucketQueue<Key, Place, Level> open_;
  std::uint32_t number_ = 0;
};

/// The hidden obstacles within the sensor radius of the robot that the known map lacks; they
/// become known. Scanning the hidden world is the benchmark's, not a planner's, work.
std::vector<VoxelIndex> sense(const World& hidden, World& known, const VoxelIndex& at)
{
  std::vector<VoxelIndex> revealed;
  for (int z = std::max(0, at.z() - kSensorRadius); z <= std::min(kN - 1, at.z() + kSensorRadius); ++z) {
    for (int y = std::max(0, at.y() - kSensorRadius); y <= std::min(kN - 1, at.y() + kSensorRadius); ++y) {
      for (int x = std::max(0, at.x() - kSensorRadius); x <= std::min(kN - 1, at.x() + kSensorRadius); ++x) {
        if (hidden.at(x, y, z) && !known.at(x, y, z)) {
          known.set(x, y, z);
          revealed.emplace_back(x, y, z);
        }
      }
    }
  }
  return revealed;
}

double secondsSince(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void navigate(benchmark::State& state, const World& hidden, Heuristic heuristic)
{
  std::uint64_t replans = 0, reached = 0, mismatches = 0;
  std::uint64_t d_expansions = 0, d_rekeys = 0, d_pushes = 0, a_expansions = 0, a_pushes = 0;
  double u_seconds = 0.0, au_seconds = 0.0, d_seconds = 0.0, a_seconds = 0.0, cost_sum = 0.0, search_bytes = 0.0, queued = 0.0;
  // The first replan of each run apart: D* Lite's first search is a search from the goal, whose
  // cost depends on where the obstacles known then lie, and it is paid once per goal.
  double d_first_seconds = 0.0, a_first_seconds = 0.0;
  std::uint64_t d_first_expansions = 0, a_first_expansions = 0, backward_first_expansions = 0;
  for (auto _ : state) {
    const Lattice lattice(VoxelGrid(1.0), Vector3(0, 0, 0), Vector3(kN, kN, kN));
    DStarLite planner(lattice, {26, true, 0.0, heuristic});
    // A*'s own map: the same graph, kept by a planner that has no goal and so repairs no
    // search when a cell changes. Each side pays for keeping its map; D* Lite also for its
    // repairs.
    DStarLite graph(lattice, {26, true, 0.0, heuristic});
    AStar astar(graph);
    World known;
    VoxelIndex robot(1, 1, 50);
    const Cell goal = *planner.lattice().cell(VoxelIndex(kN - 2, kN - 2, 50));
    planner.setGoal(goal);
    for (int step = 0; step < kMaxSteps; ++step) {
      // Each planner is charged for updating its map with what was revealed: for A* the
      // cells' blocking, for D* Lite the same and its edge repairs.
      const std::vector<VoxelIndex> revealed = sense(hidden, known, robot);
      auto t0 = std::chrono::steady_clock::now();
      for (const VoxelIndex& v : revealed) {
        planner.updateVoxel(v, Occupancy::kOccupied);
      }
      u_seconds += secondsSince(t0);
      const Cell start = *planner.lattice().cell(robot);
      planner.setStart(start);
      const PlanResult d = planner.plan();
      const double d_replan = secondsSince(t0);
      d_seconds += d_replan;
      t0 = std::chrono::steady_clock::now();
      for (const VoxelIndex& v : revealed) {
        graph.updateVoxel(v, Occupancy::kOccupied);
      }
      au_seconds += secondsSince(t0);
      const AStarResult a = astar.plan(start, goal);
      const double a_replan = secondsSince(t0);
      a_seconds += a_replan;
      if (step == 0) {
        d_first_seconds += d_replan;
        a_first_seconds += a_replan;
        d_first_expansions += d.expansions;
        a_first_expansions += a.expansions;
        // Not timed: A* from the goal to the start, the direction D* Lite searches in.
        backward_first_expansions += astar.plan(goal, start).expansions;
      }
      ++replans;
      d_expansions += d.expansions;
      d_rekeys += d.rekeys;
      d_pushes += d.heap_pushes;
      a_expansions += a.expansions;
      a_pushes += a.pushes;
      cost_sum += d.cost;
      queued += static_cast<double>(planner.queued());
      mismatches += std::abs(d.cost - a.cost) > 1e-6 ? 1U : 0U;
      if (d.status != PlanStatus::kOk || d.cells.size() < 2) {
        reached += d.status == PlanStatus::kOk ? 1U : 0U;
        break;
      }
      robot = planner.lattice().voxel(d.cells[std::min<std::size_t>(2, d.cells.size() - 1)]);  // two cells a step
    }
    search_bytes += static_cast<double>(planner.searchBytes());
  }
  const auto per = [&](double v) { return v / static_cast<double>(replans); };
  state.counters["replans"] = static_cast<double>(replans) / static_cast<double>(state.iterations());
  state.counters["goal_reached"] = static_cast<double>(reached) / static_cast<double>(state.iterations());
  state.counters["dstar_expansions"] = per(static_cast<double>(d_expansions));
  state.counters["astar_expansions"] = per(static_cast<double>(a_expansions));
  state.counters["dstar_rekeys"] = per(static_cast<double>(d_rekeys));
  state.counters["dstar_pushes"] = per(static_cast<double>(d_pushes));
  state.counters["astar_pushes"] = per(static_cast<double>(a_pushes));
  state.counters["dstar_ms"] = 1e3 * per(d_seconds);
  state.counters["dstar_update_ms"] = 1e3 * per(u_seconds);  // of dstar_ms: the map updates
  state.counters["dstar_queue"] = per(queued);
  state.counters["astar_ms"] = 1e3 * per(a_seconds);
  state.counters["astar_update_ms"] = 1e3 * per(au_seconds);  // of astar_ms: the map updates
  state.counters["expansion_ratio"] = static_cast<double>(a_expansions) / static_cast<double>(d_expansions);
  state.counters["time_ratio"] = a_seconds / d_seconds;
  const auto iterations = static_cast<double>(state.iterations());
  state.counters["dstar_first_ms"] = 1e3 * d_first_seconds / iterations;
  state.counters["astar_first_ms"] = 1e3 * a_first_seconds / iterations;
  state.counters["dstar_first_expansions"] = static_cast<double>(d_first_expansions) / iterations;
  state.counters["astar_first_expansions"] = static_cast<double>(a_first_expansions) / iterations;
  state.counters["astar_backward_first_expansions"] = static_cast<double>(backward_first_expansions) / iterations;
  state.counters["time_ratio_after_first"] = (a_seconds - a_first_seconds) / (d_seconds - d_first_seconds);
  state.counters["dstar_search_MiB"] = search_bytes / static_cast<double>(state.iterations()) / (1 << 20);
  state.counters["cost_mismatches"] = static_cast<double>(mismatches);
  state.counters["path_cost_sum"] = cost_sum / static_cast<double>(state.iterations());
}

/// Every world with each heuristic, both planners sharing it: how much D* Lite gains over
/// repeated A* depends on how well the heuristic already guides A*. A world is built when its
/// first benchmark runs.
const bool kRegistered = [] {
  struct Case {
    const char* name;
    World (*build)();
    int iterations;
  };
  static const Case kWorlds[] = {{"forest", forest, 3}, {"facades", facades, 1}, {"overhangs", overhangs, 1}};
  const std::pair<const char*, Heuristic> heuristics[] = {{"lattice", Heuristic::kLattice},
                                                          {"euclidean", Heuristic::kEuclidean}};
  for (const auto& [heuristic_name, heuristic] : heuristics) {
    for (const Case& world : kWorlds) {
      const std::string name = std::string("BM_Navigation/") + world.name + "_" + heuristic_name;
      benchmark::RegisterBenchmark(name.c_str(),
                                   [&world, h = heuristic](benchmark::State& state) {
                                     static std::map<const Case*, World> built;
                                     auto it = built.find(&world);
                                     if (it == built.end()) {
                                       it = built.emplace(&world, world.build()).first;
                                     }
                                     navigate(state, it->second, h);
                                   })
          ->Unit(benchmark::kMillisecond)
          ->Iterations(world.iterations);
    }
  }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
