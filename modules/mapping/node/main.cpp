// SPDX-License-Identifier: BSD-3-Clause
// quad_mapping_node: OctoMap occupancy mapping with change sets for the planner.
#include "mapping_node.hpp"
#include "quad/runtime/module_main.hpp"

int main(int argc, char** argv)
{
  return quad::runtime::runModule(argc, argv, quad::mapping::mappingModule());
}
