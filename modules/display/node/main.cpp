// SPDX-License-Identifier: BSD-3-Clause
// quad_display_node: the flight in Foxglove's display schemas, for viewers and recordings.
#include "display_node.hpp"
#include "quad/runtime/module_main.hpp"

int main(int argc, char** argv)
{
  return quad::runtime::runModule(argc, argv, quad::display::displayModule());
}
