// SPDX-License-Identifier: BSD-3-Clause
// quad_container: hosts several of quad's modules in one process, on one DDS participant, and
// the run's recorder beside them when asked.
#include "control_node.hpp"
#include "display_node.hpp"
#include "estimation_node.hpp"
#include "mapping_node.hpp"
#include "planning_node.hpp"
#include "plant_node.hpp"
#include "quad/record/recorder_module.hpp"
#include "quad/runtime/module_main.hpp"

int main(int argc, char** argv)
{
  return quad::runtime::runContainer(argc, argv,
                                 {quad::plant::plantModule(), quad::estimation::estimationModule(),
                                  quad::control::controlModule(), quad::mapping::mappingModule(),
                                  quad::planning::planningModule(), quad::display::displayModule(),
                                  quad::record::recorderModule()});
}
