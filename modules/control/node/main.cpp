// SPDX-License-Identifier: BSD-3-Clause
// quad_control_node: path follower, SE(3) geometric control, mixer, modes and failsafe.
#include "control_node.hpp"

int main(int argc, char** argv)
{
  using namespace quad::control;
  return quad::dds::runNode<ControlNode>(argc, argv, "control", controlSchema(), controlConfigFrom);
}
