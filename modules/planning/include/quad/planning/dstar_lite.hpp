// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// D* Lite (Koenig & Likhachev, "D* Lite", AAAI 2002; the optimised version of their
/// Figure 4) on a 3D lattice of the quadcopter's C-space: a cell is blocked when an occupied
/// voxel lies within the vehicle radius of its centre (the C-space obstacle of a sphere), so
/// the vehicle's centre may go wherever a cell is free. Edge costs are Euclidean step
/// lengths (6-, 18- or 26-connectivity), the heuristic is the obstacle-free lattice distance
/// (consistent; see Heuristic), the key modifier k_m follows the moving start, the queue holds each cell once
/// and changes its key in place (BucketQueue), with deterministic tie-breaking (key, then cell
/// number). The search's g and rhs live in
/// pages of 4,096 consecutive cells, allocated when the search first touches one of them:
/// memory grows with the region searched, not with the box, and a lookup is two indexings.

#include <algorithm>
#include <compare>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "quad/geometry/grid.hpp"
#include "quad/geometry/voxel_table.hpp"
#include "quad/planning/bucket_queue.hpp"

namespace quad::planning {

using geometry::Lattice;
using geometry::Vector3;
using geometry::VoxelIndex;
using Cell = std::int64_t;

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

enum class Occupancy : std::uint8_t { kUnknown, kFree, kOccupied };

/// kLattice: the length of the shortest path in the obstacle-free lattice (for 26 neighbours
/// √3·d3 + √2·(d2 − d3) + (d1 − d2) over the sorted axis steps), exact where nothing is in the
/// way. kEuclidean: the straight line, up to 11 % shorter; kept to compare against.
/// Both are consistent and obey the triangle inequality that k_m needs.
enum class Heuristic { kLattice, kEuclidean };

struct PlannerConfig {
  int connectivity = 26;            ///< 6, 18 or 26
  bool unknown_traversable = true;  ///< optimistic about unknown space
  double vehicle_radius = 0.35;     ///< [m] inflation
  Heuristic heuristic = Heuristic::kLattice;
};

/// kGoalEnclosed and kStartEnclosed: the search ran out, so no chain of traversable cells
/// (free, or unknown when unknown_traversable) joins start and goal; blocked cells (known
/// occupied space, inflated) seal one of them in, the one whose side is the smaller.
/// kNoPath: the search's values are not yet consistent along the way (a passing state).
enum class PlanStatus {
  kOk,
  kNoPath,
  kStartBlocked,
  kGoalBlocked,
  kOutOfBounds,
  kNoGoal,
  kBudgetExceeded,
  kGoalEnclosed,
  kStartEnclosed
};
std::string_view toString(PlanStatus s);

struct PlanResult {
  PlanStatus status = PlanStatus::kNoGoal;
  std::vector<Cell> cells;          ///< start first, goal last (when kOk)
  double cost = kInfinity;          ///< [m]
  std::uint64_t expansions = 0;     ///< vertices expanded (g settled or raised) by this replan
  std::uint64_t rekeys = 0;         ///< queue entries whose key was out of date, given their key now
  std::uint64_t heap_pushes = 0;    ///< cells queued or given a new key
};

class DStarLite {
public:
  /// Throws std::invalid_argument on a connectivity other than 6, 18, 26 or a bad radius.
  DStarLite(Lattice lattice, PlannerConfig config);

  const Lattice& lattice() const { return lattice_; }

  /// A voxel's classification changed (from the mapper's change sets). Updates the
  /// inflated blocking of the cells within the radius and the edges around every cell whose
  /// traversability changed. Voxels outside the lattice still block cells inside it.
  void updateVoxel(const VoxelIndex& voxel, Occupancy state);

  /// The cells kept out of besides the map's (deconfliction.hpp: the tubes of the vehicles
  /// this one yields to), replacing the previous set; the edges of every cell whose
  /// traversability changed are repaired as a map change repairs them.
  void setKeepOut(std::vector<Cell> cells);
  /// The cells kept out of now, sorted.
  const std::vector<Cell>& keepOut() const { return keep_out_; }

  /// Sets the goal; a new goal re-initialises the search.
  void setGoal(Cell goal);
  /// Moves the start (every replan): k_m grows by the heuristic between old and new start.
  void setStart(Cell start);

  /// Repairs the search and extracts the path. `max_expansions` bounds the work (0: none);
  /// when it runs out the status is kBudgetExceeded and the next call continues.
  PlanResult plan(std::uint64_t max_expansions = 0);

  bool traversable(Cell c) const;
  /// The mapper's classification of a voxel as the planner last heard it (inside the
  /// lattice or not; unknown when never heard of).
  Occupancy voxelState(const VoxelIndex& voxel) const;
  /// The traversable cell nearest to c (c itself when traversable), searching out to
  /// `max_distance` [m]; for a vehicle that drifted into an inflated margin.
  std::optional<Cell> nearestTraversable(Cell c, double max_distance) const;
  double edgeCost(Cell a, Cell b) const;  ///< kInfinity when either end is blocked or not neighbours
  /// Neighbours of c inside the lattice with the step length to each.
  void neighbours(Cell c, std::vector<std::pair<Cell, double>>& out) const;
  double heuristic(Cell a, Cell b) const;
  /// A cell's position in the lattice (0 ... dims − 1 per axis); no bounds check.
  Eigen::Vector3i coordinates(Cell c) const;
  /// The heuristic distance [m] between two positions in the lattice (PlannerConfig::heuristic).
  double distance(const Eigen::Vector3i& a, const Eigen::Vector3i& b) const;

  /// Cells in the search's queue (inconsistent: g ≠ rhs).
  std::size_t queued() const { return open_.size(); }
  /// Bytes of the search's per-cell state (g, rhs, queue bookkeeping) now allocated.
  std::size_t searchBytes() const;

private:
  /// Keys compare with a tolerance far above rounding and far below any difference of two
  /// lattice path costs: costs are sums of square roots, so two keys that are equal in exact
  /// arithmetic (a straight path and its heuristic, say) can differ in the last bit, and a
  /// strict comparison would then leave a cell of the optimal path unexpanded.
  static constexpr double kKeyTolerance = 1e-9;  // [m]
  static constexpr int kPageBits = 12;            // 4,096 cells a page
  struct Key {
    double k1;
    double k2;
    std::weak_ordering operator<=>(const Key& o) const
    {
      if (k1 < o.k1 - kKeyTolerance) {
        return std::weak_ordering::less;
      }
      if (k1 > o.k1 + kKeyTolerance) {
        return std::weak_ordering::greater;
      }
      if (k2 < o.k2 - kKeyTolerance) {
        return std::weak_ordering::less;
      }
      return k2 > o.k2 + kKeyTolerance ? std::weak_ordering::greater : std::weak_ordering::equivalent;
    }
  };
  /// A cell's search state.
  struct Vertex {
    double g = kInfinity;
    double rhs = kInfinity;
    QueuePlace place;  ///< its place in the queue
  };
  /// Finds a queued cell's place. Holds the pages' array, which is sized once at construction
  /// and keeps its address when the planner is moved.
  struct VertexPlace {
    std::unique_ptr<Vertex[]>* pages;
    QueuePlace& operator()(Cell c) const
    {
      return pages[static_cast<std::size_t>(c >> kPageBits)][static_cast<std::size_t>(c & ((Cell{1} << kPageBits) - 1))]
          .place;
    }
  };
  /// A key's bucket in the queue: its first component in steps of kBucketWidth lattice cells.
  /// The offset keeps the buckets' bounds off the keys that straight paths along the axes
  /// give (whole numbers of cells), where keys equal but for rounding would split.
  struct KeyLevel {
    double per_metre;
    std::uint32_t operator()(const Key& k) const
    {
      constexpr double kLast = 1 << 24;
      return static_cast<std::uint32_t>(std::min(k.k1 * per_metre + 0.38196601125, kLast));
    }
  };
  static constexpr double kBucketWidth = 1.0;
  /// Division of a 32-bit cell number by a fixed divisor as a multiplication: the quotient is
  /// the high half of n times ⌈2⁶⁴ / d⌉, exact for every 32-bit n (Lemire, Kaser & Kurz,
  /// "Faster remainder by direct computation", 2019). A search asks for coordinates at every
  /// step, and a division instruction costs several times a multiplication.
  struct Divisor {
    __extension__ typedef unsigned __int128 Wide;  // GCC's and Clang's; not ISO C++
    std::uint32_t d = 1;
    std::uint64_t m = 0;  // ⌈2⁶⁴ / d⌉; unused for d = 1
    explicit Divisor(std::uint32_t divisor = 1) : d(divisor), m(divisor > 1 ? ~std::uint64_t{0} / divisor + 1 : 0) {}
    std::uint32_t divide(std::uint32_t n) const
    {
      return d == 1 ? n : static_cast<std::uint32_t>((static_cast<Wide>(m) * n) >> 64);
    }
  };
  /// A neighbour offset: steps along the axes, the cell-number difference, the step length.
  struct Step {
    int dx, dy, dz;
    Cell delta;
    double cost;
  };

  /// The state of c, nullptr when the search never touched c's page (g = rhs = ∞).
  const Vertex* find(Cell c) const
  {
    const auto& page = pages_[static_cast<std::size_t>(c >> kPageBits)];
    return page ? &page[static_cast<std::size_t>(c & ((Cell{1} << kPageBits) - 1))] : nullptr;
  }
  Vertex* find(Cell c) { return const_cast<Vertex*>(std::as_const(*this).find(c)); }
  Vertex& vertex(Cell c);  ///< allocates c's page on first touch
  /// f(neighbour, step) for each neighbour of c inside the lattice, in the order of their
  /// cell numbers; p: c's coordinates. An f that returns bool stops the scan by returning false.
  template <typename F>
  void forEachStep(Cell c, const Eigen::Vector3i& p, F&& f) const;
  /// f(neighbour, step length) for each neighbour of c inside the lattice.
  template <typename F>
  void forEachNeighbour(Cell c, F&& f) const;

  double g(Cell c) const;
  double rhs(Cell c) const;
  Key calculateKey(Cell c) const;
  Key keyOf(const Vertex& v, const Eigen::Vector3i& p) const;  ///< p: v's coordinates
  /// rhs(u) from scratch: min over successors of c(u, s') + g(s'). `floor`: a value rhs(u)
  /// cannot fall below (its old value, when only costs rose); the scan stops at a successor
  /// that gives it.
  double bestRhs(Cell u, double floor = -kInfinity) const;
  void setRhs(Cell u, double value);
  void queue(Cell u, const Key& k);
  /// UpdateVertex of the optimised version: (re)queue u when inconsistent, drop it when not.
  void updateVertex(Cell u);
  void updateVertex(Cell u, const Vertex& v, const Eigen::Vector3i& p);  ///< p: u's coordinates
  /// Every edge touching c changed (c became blocked or free): the paper's edge-update rules.
  void cellChanged(Cell c, bool blocked);
  void reset();

  Lattice lattice_;
  PlannerConfig config_;
  Eigen::Vector3i dims_;
  Cell size_;                                 // cells in the lattice
  Cell nxy_;                                  // cells in a layer of z
  bool narrow_;                               // cell numbers fit 32 bits
  Divisor by_nx_;                             // for narrow_ lattices: by dims_.x()
  Divisor by_nxy_;                            // and by nxy_
  Eigen::Vector3i start_coordinates_ = Eigen::Vector3i::Zero();  // of start_, for the keys
  std::vector<Step> steps_;                   // neighbour offsets
  std::vector<VoxelIndex> inflation_;         // inflation offsets
  // Per cell, flat over the lattice (3 bytes a cell): occupied voxels blocking it, and the
  // classification of its own voxel. Traversability is asked for every edge: no hashing.
  std::vector<std::uint16_t> blockers_;
  std::vector<Occupancy> cell_state_;
  std::vector<Cell> changed_;  // updateVoxel's cells whose traversability changed, reused
  // Per cell, 1 where setKeepOut keeps the search out; empty until the first keep-out, so a
  // lone vehicle's planner spends nothing on it.
  std::vector<std::uint8_t> kept_out_;
  std::vector<Cell> keep_out_;  // its cells, sorted
  // The classification of voxels outside the lattice (its own cells' are cell_state_), for
  // the inflation and known-space checks that reach past its sides; within 2^19 voxels of
  // the origin, as every map's (an OctoMap's reach is 2^15).
  geometry::VoxelTable voxels_;
  std::vector<std::unique_ptr<Vertex[]>> pages_;
  std::size_t allocated_pages_ = 0;
  BucketQueue<Key, VertexPlace, KeyLevel> open_;
  std::optional<Cell> start_;
  std::optional<Cell> goal_;
  std::optional<Cell> last_;
  double km_ = 0.0;
  std::uint64_t pushes_ = 0;
};

/// Which of two cells is sealed in: floods the traversable cells reachable from each in turn,
/// one cell at a time, until one side runs out (or the floods meet: then neither, nullopt).
/// Costs about twice the smaller side, so a goal sealed in a room is told cheaply even in a
/// large box. Returns `a` or `b`, the one whose side ran out first.
std::optional<Cell> sealedIn(const DStarLite& graph, Cell a, Cell b);

/// Dijkstra from scratch on the same graph: the reference D* Lite's costs are checked against.
double shortestPathCost(const DStarLite& graph, Cell start, Cell goal);

}  // namespace quad::planning
