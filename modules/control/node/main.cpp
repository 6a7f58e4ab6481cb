// SPDX-License-Identifier: BSD-3-Clause
// quad_control_node: path follower, SE(3) geometric control, mixer, modes and failsafe.
#include "control_node.hpp"
#include "quad/runtime/module_main.hpp"

int main(int argc, char** argv)
{
  return quad::runtime::runModule(argc, argv, quad::control::controlModule());
}
