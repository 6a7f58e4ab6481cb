// SPDX-License-Identifier: BSD-3-Clause
// quad_plant_node: the simulated quadrotor, its world and sensors, and the sim clock.
#include "plant_node.hpp"

int main(int argc, char** argv)
{
  using namespace quad::plant;
  return quad::dds::runNode<PlantNode>(argc, argv, "plant", plantSchema(), plantConfigFrom);
}
