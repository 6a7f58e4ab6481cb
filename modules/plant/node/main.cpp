// SPDX-License-Identifier: BSD-3-Clause
// quad_plant_node: the simulated quadrotor, its world and sensors, and the sim clock.
#include "plant_node.hpp"
#include "quad/runtime/module_main.hpp"

int main(int argc, char** argv)
{
  return quad::runtime::runModule(argc, argv, quad::plant::plantModule());
}
