// SPDX-License-Identifier: BSD-3-Clause
#include "quad/display/display_params.hpp"

namespace quad::display {

const common::ParamTable<DisplayParams>& displayTable()
{
  using P = DisplayParams;
  static const common::ParamTable<P> table = [] {
    common::ParamTable<P> t;
    t.path("world", [](P& p) -> std::filesystem::path& { return p.world_file; },
           "world file whose obstacles are drawn (empty: none)")
        .number("transforms.rate", [](P& p) -> double& { return p.transforms_rate; }, {0.1, 1000.0}, "Hz",
                "frame transforms per second of sim time")
        .number("trajectory.rate", [](P& p) -> double& { return p.trajectory_rate; }, {0.01, 100.0}, "Hz",
                "trajectories sent whole per second of sim time")
        .number("map.rate", [](P& p) -> double& { return p.map_rate; }, {0.01, 100.0}, "Hz",
                "occupied voxels sent whole per second of sim time, at most (when they changed)")
        .number("trajectory.spacing", [](P& p) -> double& { return p.trace.spacing; }, {0.001, 100.0}, "m",
                "a pose is kept once the vehicle moved this far from the last kept")
        .number("trajectory.turn", [](P& p) -> double& { return p.trace.turn; }, {0.001, 3.2}, "rad",
                "... or turned this much")
        .number("trajectory.max_poses", [](P& p) -> std::size_t& { return p.trace.max_poses; }, {2, 65536}, "",
                "beyond it every other pose is dropped and the spacing doubles")
        .number("goal.radius", [](P& p) -> double& { return p.goal_radius; }, {0.01, 100.0}, "m",
                "radius of the goal's sphere");
    return t;
  }();
  return table;
}

}  // namespace quad::display
