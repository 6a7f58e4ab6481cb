// SPDX-License-Identifier: BSD-3-Clause
// quad_planning_node: D* Lite over the mapper's change sets, paths to the controller.
#include "planning_node.hpp"

int main(int argc, char** argv)
{
  using namespace quad::planning;
  return quad::dds::runNode<PlanningNode>(argc, argv, "planning", planningNodeSchema(), planningConfigFrom);
}
