// quad_mapping_node: OctoMap occupancy mapping with change sets for the planner.
#include "mapping_node.hpp"

int main(int argc, char** argv)
{
  return quad::dds::runNodeMain(argc, argv, "mapping", quad::mapping::mappingSchema(),
                                [](const quad::common::Params& params) {
                                  return std::make_unique<quad::mapping::MappingNode>(
                                      quad::mapping::mappingConfigFrom(params),
                                      quad::dds::optionsFromEnvironment("mapping"));
                                });
}
