// SPDX-License-Identifier: BSD-3-Clause
#include "quad/planning/shortcut.hpp"

#include <cmath>

namespace quad::planning {

bool lineOfSight(const DStarLite& planner, const Vector3& a, const Vector3& b)
{
  const double step = planner.lattice().grid().resolution() / 4.0;
  const double length = (b - a).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
  for (int i = 0; i <= n; ++i) {
    const Vector3 p = a + (b - a) * (static_cast<double>(i) / n);
    const auto cell = planner.lattice().cellAt(p);
    if (!cell || !planner.traversable(*cell)) {
      return false;
    }
  }
  return true;
}

std::vector<Vector3> shortcut(const DStarLite& planner, const std::vector<Cell>& cells)
{
  std::vector<Vector3> out;
  if (cells.empty()) {
    return out;
  }
  out.push_back(planner.lattice().centre(cells.front()));
  std::size_t anchor = 0;
  for (std::size_t i = 1; i < cells.size(); ++i) {
    const bool last = i + 1 == cells.size();
    if (!last && lineOfSight(planner, planner.lattice().centre(cells[anchor]), planner.lattice().centre(cells[i + 1]))) {
      continue;  // cells[i] can be skipped
    }
    out.push_back(planner.lattice().centre(cells[i]));
    anchor = i;
  }
  return out;
}

}  // namespace quad::planning
