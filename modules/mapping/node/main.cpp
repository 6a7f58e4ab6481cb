// SPDX-License-Identifier: BSD-3-Clause
// quad_mapping_node: OctoMap occupancy mapping with change sets for the planner.
#include "mapping_node.hpp"

int main(int argc, char** argv)
{
  using namespace quad::mapping;
  return quad::dds::runNode<MappingNode>(argc, argv, "mapping", mappingSchema(), mappingConfigFrom);
}
