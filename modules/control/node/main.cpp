// quad_control_node: path follower, SE(3) geometric control, mixer, modes and failsafe.
#include "control_node.hpp"

int main(int argc, char** argv)
{
  return quad::dds::runNodeMain(argc, argv, "control", quad::control::controlSchema(),
                                [](const quad::common::Params& params) {
                                  return std::make_unique<quad::control::ControlNode>(
                                      quad::control::controlConfigFrom(params),
                                      quad::dds::optionsFromEnvironment("control"));
                                });
}
