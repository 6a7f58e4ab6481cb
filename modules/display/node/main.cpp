// SPDX-License-Identifier: BSD-3-Clause
// quad_display_node: the flight in Foxglove's display schemas, for viewers and recordings.
#include "display_node.hpp"

int main(int argc, char** argv)
{
  using namespace quad::display;
  return quad::dds::runNode<DisplayNode>(argc, argv, "display", displayNodeSchema(), displayConfigFrom);
}
