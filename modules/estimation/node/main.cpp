// SPDX-License-Identifier: BSD-3-Clause
// quad_estimation_node: the vehicle's state fused from the plant's noisy sensors.
#include "estimation_node.hpp"

int main(int argc, char** argv)
{
  using namespace quad::estimation;
  return quad::dds::runNode<EstimationNode>(argc, argv, "estimation", estimatorSchema(), estimatorParamsOf);
}
