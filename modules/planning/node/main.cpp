// quad_planning_node: D* Lite over the mapper's change sets, paths to the controller.
#include "planning_node.hpp"

int main(int argc, char** argv)
{
  return quad::dds::runNodeMain(argc, argv, "planning", quad::planning::planningSchema(),
                                [](const quad::common::Params& params) {
                                  return std::make_unique<quad::planning::PlanningNode>(
                                      quad::planning::planningConfigFrom(params),
                                      quad::dds::optionsFromEnvironment("planning"));
                                });
}
