// quad_plant_node: the simulated quadrotor, its world and sensors, and the sim clock.
#include "plant_node.hpp"

int main(int argc, char** argv)
{
  return quad::dds::runNodeMain(argc, argv, "plant", quad::plant::plantSchema(),
                                [](const quad::common::Params& params) {
                                  return std::make_unique<quad::plant::PlantNode>(
                                      quad::plant::plantConfigFrom(params),
                                      quad::dds::optionsFromEnvironment("plant"));
                                });
}
