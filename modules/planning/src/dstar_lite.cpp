// SPDX-License-Identifier: BSD-3-Clause
#include "quad/planning/dstar_lite.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <queue>
#include <stdexcept>
#include <type_traits>
#include <unordered_map>

#include "quad/geometry/inflation.hpp"

namespace quad::planning {

std::string_view toString(PlanStatus s)
{
  switch (s) {
    case PlanStatus::kOk:
      return "ok";
    case PlanStatus::kNoPath:
      return "no path";
    case PlanStatus::kStartBlocked:
      return "start blocked";
    case PlanStatus::kGoalBlocked:
      return "goal blocked";
    case PlanStatus::kOutOfBounds:
      return "out of bounds";
    case PlanStatus::kNoGoal:
      return "no goal";
    case PlanStatus::kBudgetExceeded:
      return "budget exceeded";
    case PlanStatus::kGoalEnclosed:
      return "goal enclosed";
    case PlanStatus::kStartEnclosed:
      return "start enclosed";
  }
  return "?";
}

DStarLite::DStarLite(Lattice lattice, PlannerConfig config)
    : lattice_(std::move(lattice)),
      config_(config),
      dims_(lattice_.dims()),
      size_(lattice_.size()),
      nxy_(Cell{dims_.x()} * dims_.y()),
      narrow_(size_ <= std::numeric_limits<std::uint32_t>::max()),
      by_nx_(narrow_ ? static_cast<std::uint32_t>(dims_.x()) : 1),
      by_nxy_(narrow_ ? static_cast<std::uint32_t>(nxy_) : 1),
      pages_(static_cast<std::size_t>((size_ >> kPageBits) + 1)),
      open_(VertexPlace{pages_.data()}, KeyLevel{1.0 / (kBucketWidth * lattice_.grid().resolution())})
{
  if (config_.connectivity != 6 && config_.connectivity != 18 && config_.connectivity != 26) {
    throw std::invalid_argument("planner connectivity " + std::to_string(config_.connectivity) + ": expected 6, 18 or 26");
  }
  if (!(config_.vehicle_radius >= 0.0) || !std::isfinite(config_.vehicle_radius)) {
    throw std::invalid_argument("planner vehicle radius must be finite and >= 0");
  }
  const double res = lattice_.grid().resolution();
  const Cell nx = dims_.x();
  const Cell nxy = nx * dims_.y();
  for (int dz = -1; dz <= 1; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int nonzero = (dx != 0) + (dy != 0) + (dz != 0);
        if (nonzero == 0 || (config_.connectivity == 6 && nonzero > 1) || (config_.connectivity == 18 && nonzero > 2)) {
          continue;
        }
        steps_.push_back({dx, dy, dz, dx + nx * dy + nxy * dz, res * std::sqrt(static_cast<double>(nonzero))});
      }
    }
  }
  inflation_ = geometry::inflationOffsets(config_.vehicle_radius, res);
  blockers_.assign(static_cast<std::size_t>(lattice_.size()), 0);
  cell_state_.assign(static_cast<std::size_t>(lattice_.size()), Occupancy::kUnknown);
}

Eigen::Vector3i DStarLite::coordinates(Cell c) const
{
  // Two divisions, as multiplications where the lattice's cells are numbered in 32 bits.
  if (narrow_) {
    const auto n = static_cast<std::uint32_t>(c);
    const std::uint32_t z = by_nxy_.divide(n), rest = n - z * by_nxy_.d, y = by_nx_.divide(rest);
    return {static_cast<int>(rest - y * by_nx_.d), static_cast<int>(y), static_cast<int>(z)};
  }
  const Cell nx = dims_.x();
  const Cell z = c / nxy_, rest = c - z * nxy_, y = rest / nx;
  return {static_cast<int>(rest - y * nx), static_cast<int>(y), static_cast<int>(z)};
}

template <typename F>
void DStarLite::forEachStep(Cell c, const Eigen::Vector3i& p, F&& f) const
{
  const bool interior = p.x() > 0 && p.y() > 0 && p.z() > 0 && p.x() + 1 < dims_.x() && p.y() + 1 < dims_.y() &&
                        p.z() + 1 < dims_.z();
  for (const Step& s : steps_) {
    if (interior || (static_cast<unsigned>(p.x() + s.dx) < static_cast<unsigned>(dims_.x()) &&
                     static_cast<unsigned>(p.y() + s.dy) < static_cast<unsigned>(dims_.y()) &&
                     static_cast<unsigned>(p.z() + s.dz) < static_cast<unsigned>(dims_.z()))) {
      if constexpr (std::is_same_v<std::invoke_result_t<F, Cell, const Step&>, bool>) {
        if (!f(c + s.delta, s)) {
          return;  // f asked to stop
        }
      } else {
        f(c + s.delta, s);
      }
    }
  }
}

template <typename F>
void DStarLite::forEachNeighbour(Cell c, F&& f) const
{
  forEachStep(c, coordinates(c), [&](Cell n, const Step& s) { f(n, s.cost); });
}

DStarLite::Vertex& DStarLite::vertex(Cell c)
{
  auto& page = pages_[static_cast<std::size_t>(c >> kPageBits)];
  if (!page) {
    page = std::make_unique<Vertex[]>(std::size_t{1} << kPageBits);
    ++allocated_pages_;
  }
  return page[static_cast<std::size_t>(c & ((Cell{1} << kPageBits) - 1))];
}

std::size_t DStarLite::searchBytes() const { return allocated_pages_ * (std::size_t{1} << kPageBits) * sizeof(Vertex); }

bool DStarLite::traversable(Cell c) const
{
  if (c < 0 || c >= size_) {
    return false;
  }
  const auto i = static_cast<std::size_t>(c);
  return blockers_[i] == 0 && (config_.unknown_traversable || cell_state_[i] != Occupancy::kUnknown) &&
         (kept_out_.empty() || kept_out_[i] == 0);
}

void DStarLite::setKeepOut(std::vector<Cell> cells)
{
  std::erase_if(cells, [&](Cell c) { return c < 0 || c >= size_; });
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  if (cells == keep_out_) {
    return;
  }
  if (kept_out_.empty()) {
    kept_out_.assign(static_cast<std::size_t>(size_), 0);
  }
  // Every cell that was or is now kept out, with its traversability before the change.
  std::vector<Cell> touched;
  touched.reserve(cells.size() + keep_out_.size());
  std::set_union(keep_out_.begin(), keep_out_.end(), cells.begin(), cells.end(), std::back_inserter(touched));
  std::vector<bool> was(touched.size());
  for (std::size_t k = 0; k < touched.size(); ++k) {
    was[k] = traversable(touched[k]);
  }
  for (const Cell c : keep_out_) {
    kept_out_[static_cast<std::size_t>(c)] = 0;
  }
  for (const Cell c : cells) {
    kept_out_[static_cast<std::size_t>(c)] = 1;
  }
  keep_out_ = std::move(cells);
  for (std::size_t k = 0; k < touched.size(); ++k) {
    if (was[k] != traversable(touched[k])) {
      cellChanged(touched[k], was[k]);
    }
  }
}

// An outside voxel's Occupancy is its table state: none is unknown.
static_assert(static_cast<int>(Occupancy::kUnknown) == 0);

Occupancy DStarLite::voxelState(const VoxelIndex& voxel) const
{
  if (const auto c = lattice_.cell(voxel)) {
    return cell_state_[static_cast<std::size_t>(*c)];
  }
  return static_cast<Occupancy>(voxels_.get(voxel));
}

std::optional<Cell> DStarLite::nearestTraversable(Cell c, double max_distance) const
{
  if (traversable(c)) {
    return c;
  }
  const double res = lattice_.grid().resolution();
  const VoxelIndex v = lattice_.voxel(c);
  std::optional<Cell> best;
  double best_d = kInfinity;
  const int reach = static_cast<int>(std::ceil(max_distance / res));
  for (int dz = -reach; dz <= reach; ++dz) {
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        const double d = res * std::sqrt(static_cast<double>(dx * dx + dy * dy + dz * dz));
        if (d > max_distance || d >= best_d) {
          continue;
        }
        const auto n = lattice_.cell(v + VoxelIndex(dx, dy, dz));
        if (n && traversable(*n)) {
          best = n;
          best_d = d;
        }
      }
    }
  }
  return best;
}

void DStarLite::neighbours(Cell c, std::vector<std::pair<Cell, double>>& out) const
{
  out.clear();
  forEachNeighbour(c, [&](Cell n, double step) { out.emplace_back(n, step); });
}

double DStarLite::edgeCost(Cell a, Cell b) const
{
  if (!traversable(a) || !traversable(b)) {
    return kInfinity;
  }
  const Eigen::Vector3i d = (coordinates(a) - coordinates(b)).cwiseAbs();
  const int nonzero = (d.x() != 0) + (d.y() != 0) + (d.z() != 0);
  if (d.maxCoeff() != 1 || (config_.connectivity == 6 && nonzero > 1) || (config_.connectivity == 18 && nonzero > 2)) {
    return kInfinity;
  }
  return lattice_.grid().resolution() * std::sqrt(static_cast<double>(nonzero));
}

double DStarLite::heuristic(Cell a, Cell b) const { return distance(coordinates(a), coordinates(b)); }

double DStarLite::distance(const Eigen::Vector3i& a, const Eigen::Vector3i& b) const
{
  const double res = lattice_.grid().resolution();
  if (config_.heuristic == Heuristic::kEuclidean) {
    return res * (a - b).cast<double>().norm();
  }
  // The shortest path in the obstacle-free lattice: with the steps along the axes sorted,
  // d1 >= d2 >= d3, as many of the longest moves as the displacement allows.
  std::array<int, 3> d{std::abs(a.x() - b.x()), std::abs(a.y() - b.y()), std::abs(a.z() - b.z())};
  if (d[0] < d[1]) {
    std::swap(d[0], d[1]);
  }
  if (d[1] < d[2]) {
    std::swap(d[1], d[2]);
  }
  if (d[0] < d[1]) {
    std::swap(d[0], d[1]);
  }
  static const double kSqrt2 = std::sqrt(2.0);
  static const double kSqrt3 = std::sqrt(3.0);
  switch (config_.connectivity) {
    case 6:
      return res * (d[0] + d[1] + d[2]);
    case 18: {
      // Each diagonal move covers two axes; at most sum/2 of them, and d1 cannot pair with itself.
      const int sum = d[0] + d[1] + d[2];
      const int diagonals = std::min(sum / 2, sum - d[0]);
      return res * (kSqrt2 * diagonals + (sum - 2 * diagonals));
    }
    default:
      return res * (kSqrt3 * d[2] + kSqrt2 * (d[1] - d[2]) + (d[0] - d[1]));
  }
}

double DStarLite::g(Cell c) const
{
  const Vertex* v = find(c);
  return v ? v->g : kInfinity;
}

double DStarLite::rhs(Cell c) const
{
  const Vertex* v = find(c);
  return v ? v->rhs : kInfinity;
}

DStarLite::Key DStarLite::calculateKey(Cell c) const
{
  const Vertex* v = find(c);
  return keyOf(v ? *v : Vertex{}, coordinates(c));
}

DStarLite::Key DStarLite::keyOf(const Vertex& v, const Eigen::Vector3i& p) const
{
  const double m = std::min(v.g, v.rhs);
  return {m + distance(p, start_coordinates_) + km_, m};
}

double DStarLite::bestRhs(Cell u, double floor) const
{
  if (goal_ && u == *goal_) {
    return 0.0;
  }
  if (!traversable(u)) {
    return kInfinity;
  }
  double best = kInfinity;
  forEachStep(u, coordinates(u), [&](Cell n, const Step& s) {
    const Vertex* v = find(n);
    if (v != nullptr && s.cost + v->g < best && traversable(n)) {
      best = s.cost + v->g;
    }
    return best != floor;  // nothing is lower than the floor
  });
  return best;
}

void DStarLite::setRhs(Cell u, double value)
{
  if (value != kInfinity || find(u) != nullptr) {
    vertex(u).rhs = value;
  }
}

void DStarLite::queue(Cell u, const Key& k)
{
  open_.set(u, k);
  ++pushes_;
}

void DStarLite::updateVertex(Cell u)
{
  if (const Vertex* v = find(u)) {
    updateVertex(u, *v, coordinates(u));
  }
  // else g = rhs = ∞: consistent, and never queued
}

void DStarLite::updateVertex(Cell u, const Vertex& v, const Eigen::Vector3i& p)
{
  if (v.g != v.rhs) {
    queue(u, keyOf(v, p));
  } else {
    open_.remove(u);
  }
}

void DStarLite::reset()
{
  open_.clear();
  for (auto& page : pages_) {
    page.reset();
  }
  allocated_pages_ = 0;
  km_ = 0.0;
  last_ = start_;
  if (goal_) {
    vertex(*goal_).rhs = 0.0;
    if (start_) {
      queue(*goal_, calculateKey(*goal_));
    }
  }
}

void DStarLite::setGoal(Cell goal)
{
  if (goal_ && *goal_ == goal) {
    return;
  }
  goal_ = goal;
  reset();
}

void DStarLite::setStart(Cell start)
{
  if (start_ && *start_ == start) {
    return;
  }
  const bool first = !start_;
  start_ = start;
  start_coordinates_ = coordinates(start);
  if (first || !last_) {
    reset();
    return;
  }
  km_ += heuristic(*last_, start);
  last_ = start;
  open_.keysAged();
}

void DStarLite::cellChanged(Cell c, bool blocked)
{
  if (!start_ || !goal_) {
    return;
  }
  // Koenig & Likhachev 2002, Fig. 4, lines 38-48, for every edge into and out of c.
  const double gc = g(c);
  if (blocked) {
    // Costs rose to infinity: only vertices whose rhs came through the lost edge recompute.
    // None did when g(c) is infinite (the search never reached c): an rhs through c would be
    // infinite too, and recomputing it gives infinity again. Most cells a sensor reveals lie
    // there, and 26 neighbours of 26 lookups each made their repair cost more than the search.
    if (gc != kInfinity) {
      forEachNeighbour(c, [&](Cell n, double step) {
        if (n != *goal_ && rhs(n) == step + gc) {
          setRhs(n, bestRhs(n));
          updateVertex(n);
        }
      });
    }
    if (c != *goal_) {
      setRhs(c, kInfinity);  // no edge leaves a blocked cell
    }
    updateVertex(c);
  } else {
    // Costs fell: a neighbour may now do better through c, and c through its neighbours.
    forEachNeighbour(c, [&](Cell n, double step) {
      if (n != *goal_ && traversable(n) && step + gc < rhs(n)) {
        setRhs(n, step + gc);
        updateVertex(n);
      }
    });
    if (c != *goal_) {
      setRhs(c, bestRhs(c));
    }
    updateVertex(c);
  }
}

void DStarLite::updateVoxel(const VoxelIndex& voxel, Occupancy state)
{
  // A voxel inside the lattice is its cell's own state; only those outside need the map.
  const auto own = lattice_.cell(voxel);
  const Occupancy before = voxelState(voxel);
  if (before == state) {
    return;
  }
  std::vector<Cell>& changed = changed_;
  changed.clear();
  if (own) {
    const bool was = traversable(*own);
    cell_state_[static_cast<std::size_t>(*own)] = state;
    if (was != traversable(*own)) {
      changed.push_back(*own);
    }
  } else {
    voxels_.set(voxel, static_cast<std::uint8_t>(state));  // unknown: let go
  }
  if ((before == Occupancy::kOccupied) != (state == Occupancy::kOccupied)) {
    const int delta = state == Occupancy::kOccupied ? 1 : -1;
    for (const VoxelIndex& d : inflation_) {
      const auto c = lattice_.cell(voxel + d);
      if (!c) {
        continue;
      }
      const bool was = traversable(*c);
      auto& count = blockers_[static_cast<std::size_t>(*c)];
      count = static_cast<std::uint16_t>(count + delta);
      if (was != traversable(*c)) {
        changed.push_back(*c);
      }
    }
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  for (const Cell c : changed) {
    cellChanged(c, !traversable(c));
  }
}

PlanResult DStarLite::plan(std::uint64_t max_expansions)
{
  PlanResult out;
  if (!goal_) {
    out.status = PlanStatus::kNoGoal;
    return out;
  }
  if (!start_) {
    out.status = PlanStatus::kOutOfBounds;
    return out;
  }
  if (!traversable(*start_)) {
    out.status = PlanStatus::kStartBlocked;
    return out;
  }
  if (!traversable(*goal_)) {
    out.status = PlanStatus::kGoalBlocked;
    return out;
  }
  const std::uint64_t pushes_before = pushes_;
  // ComputeShortestPath, optimised version (Koenig & Likhachev 2002, Fig. 4).
  // Keys queued before the start moved are brought up to date a bucket at a time, as the
  // search reaches them: a key update (the paper's lines 13-14) without a sift.
  // A queued key's second part is min(g, rhs) as it is now (every change to a queued cell's g
  // or rhs requeues it), so the key now needs only the heuristic to the new start.
  const auto fresh = [&](const auto& entry) {
    const Key k{entry.key.k2 + distance(coordinates(entry.cell), start_coordinates_) + km_, entry.key.k2};
    if (entry.key < k) {
      ++out.rekeys;
    }
    return k;
  };
  while (!open_.empty()) {
    const auto& top = open_.top(fresh);
    const Cell u = top.cell;
    const Key k_old = top.key;
    const Vertex* vstart = find(*start_);
    const double m_start = vstart ? std::min(vstart->g, vstart->rhs) : kInfinity;
    const Key k_start{m_start + km_, m_start};  // the heuristic from the start to itself is 0
    if (!(k_old < k_start) && (vstart == nullptr || vstart->rhs <= vstart->g)) {
      break;
    }
    if (max_expansions != 0 && out.expansions + out.rekeys >= max_expansions) {
      out.status = PlanStatus::kBudgetExceeded;
      out.heap_pushes = pushes_ - pushes_before;
      return out;
    }
    Vertex& vu = vertex(u);
    const Eigen::Vector3i pu = coordinates(u);
    const Key k_new = keyOf(vu, pu);
    if (k_old < k_new) {
      // Queued before the start moved (k_m grew): requeue with its key now; not an expansion.
      queue(u, k_new);
      ++out.rekeys;
      continue;
    }
    ++out.expansions;
    if (vu.g > vu.rhs) {
      // Overconsistent: settle g, and let predecessors improve through u.
      const double gu = vu.rhs;
      vu.g = gu;
      open_.remove(u);
      if (traversable(u)) {
        forEachStep(u, pu, [&](Cell s, const Step& step) {
          const double through = step.cost + gu;
          if (s == *goal_ || !traversable(s)) {
            return;
          }
          Vertex* found = find(s);
          if (found != nullptr && !(through < found->rhs)) {
            return;
          }
          Vertex& vs = found != nullptr ? *found : vertex(s);
          vs.rhs = through;
          updateVertex(s, vs, Eigen::Vector3i(pu.x() + step.dx, pu.y() + step.dy, pu.z() + step.dz));
        });
      }
    } else {
      // Underconsistent: raise g to infinity; whoever went through u recomputes.
      const double g_old = vu.g;
      vu.g = kInfinity;
      forEachStep(u, pu, [&](Cell s, const Step& step) {
        // The paper updates every predecessor; one whose rhs did not come through u keeps its
        // g and rhs, so its queued key (a lower bound, refreshed when it reaches the top)
        // stands and its consistency is unchanged.
        if (s != *goal_ && rhs(s) == step.cost + g_old) {
          // Only u's g rose: no other successor gives less than the old value.
          setRhs(s, bestRhs(s, step.cost + g_old));
          updateVertex(s);
        }
      });
      updateVertex(u, vu, pu);  // rhs(u) does not depend on g(u): it stays, u is inconsistent now
    }
  }
  out.heap_pushes = pushes_ - pushes_before;
  out.cost = rhs(*start_);
  if (*start_ == *goal_) {
    out.cost = 0.0;
  }
  if (out.cost == kInfinity) {
    // The queue ran dry: the goal's side is exhausted and the start is not on it.
    const auto sealed = sealedIn(*this, *goal_, *start_);
    out.status = !sealed ? PlanStatus::kNoPath
                         : (*sealed == *goal_ ? PlanStatus::kGoalEnclosed : PlanStatus::kStartEnclosed);
    return out;
  }
  // Follow the gradient: argmin over successors of c(s, s') + g(s'), ties by cell number.
  // Where g is consistent it falls by every step's cost along the way; a step whose g does
  // not fall means it is not yet consistent there (it can happen beyond the start's
  // consistency), and could lead round in a circle: report no path now. g falling strictly
  // is what ends the walk, without remembering the cells visited. rhs(s) is that minimum
  // (kept so at every change of a g or an edge), and the successors come in the order of
  // their cell numbers: the first that gives rhs(s) is the one, and the rest need no look.
  Cell s = *start_;
  out.cells.push_back(s);
  double value = out.cost;  // g(s), rhs for the start
  while (s != *goal_) {
    const double least = rhs(s);
    Cell best = -1;
    double best_cost = kInfinity;
    forEachStep(s, coordinates(s), [&](Cell n, const Step& step) {
      const Vertex* v = find(n);
      const double c = v != nullptr && traversable(n) ? step.cost + v->g : kInfinity;
      if (c < best_cost) {
        best_cost = c;
        best = n;
      }
      return best_cost != least;
    });
    if (best < 0 || best_cost == kInfinity || !(g(best) < value)) {
      out.status = PlanStatus::kNoPath;
      out.cells.clear();
      return out;
    }
    s = best;
    value = g(best);
    out.cells.push_back(s);
  }
  out.status = s == *goal_ ? PlanStatus::kOk : PlanStatus::kNoPath;
  return out;
}

std::optional<Cell> sealedIn(const DStarLite& graph, Cell a, Cell b)
{
  if (!graph.traversable(a)) {
    return a;
  }
  if (!graph.traversable(b)) {
    return b;
  }
  struct Flood {
    Cell origin;
    std::vector<Cell> frontier;
    std::size_t next = 0;  // frontier[next] is expanded next
  };
  std::array<Flood, 2> floods{Flood{a, {a}}, Flood{b, {b}}};
  std::unordered_map<Cell, int> seen{{a, 0}, {b, 1}};  // which flood reached a cell
  std::vector<std::pair<Cell, double>> around;
  for (;;) {
    for (int side = 0; side < 2; ++side) {
      Flood& f = floods[static_cast<std::size_t>(side)];
      if (f.next == f.frontier.size()) {
        return f.origin;  // ran out first
      }
      graph.neighbours(f.frontier[f.next++], around);
      for (const auto& [n, step] : around) {
        if (!graph.traversable(n)) {
          continue;
        }
        const auto [it, fresh] = seen.emplace(n, side);
        if (fresh) {
          f.frontier.push_back(n);
        } else if (it->second != side) {
          return std::nullopt;  // the floods met: a path exists
        }
      }
    }
  }
}

double shortestPathCost(const DStarLite& graph, Cell start, Cell goal)
{
  if (!graph.traversable(start) || !graph.traversable(goal)) {
    return kInfinity;
  }
  std::unordered_map<Cell, double> dist{{start, 0.0}};
  using Item = std::pair<double, Cell>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  open.push({0.0, start});
  std::vector<std::pair<Cell, double>> around;
  while (!open.empty()) {
    const auto [d, u] = open.top();
    open.pop();
    if (d > dist[u]) {
      continue;
    }
    if (u == goal) {
      return d;
    }
    graph.neighbours(u, around);
    for (const auto& [v, step] : around) {
      const double c = graph.edgeCost(u, v);
      if (c == kInfinity) {
        continue;
      }
      const auto it = dist.find(v);
      if (it == dist.end() || d + c < it->second) {
        dist[v] = d + c;
        open.push({d + c, v});
      }
    }
  }
  return kInfinity;
}

}  // namespace quad::planning
