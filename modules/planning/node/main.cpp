// SPDX-License-Identifier: BSD-3-Clause
// quad_planning_node: D* Lite over the mapper's change sets, paths to the controller.
#include "planning_node.hpp"
#include "quad/runtime/module_main.hpp"

int main(int argc, char** argv)
{
  return quad::runtime::runModule(argc, argv, quad::planning::planningModule());
}
