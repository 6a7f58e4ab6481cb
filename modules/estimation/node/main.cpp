// SPDX-License-Identifier: BSD-3-Clause
// quad_estimation_node: the vehicle's state fused from the plant's noisy sensors.
#include "estimation_node.hpp"
#include "quad/runtime/module_main.hpp"

int main(int argc, char** argv)
{
  return quad::runtime::runModule(argc, argv, quad::estimation::estimationModule());
}
