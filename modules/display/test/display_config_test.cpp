// SPDX-License-Identifier: BSD-3-Clause
// configs/display.yaml: read with its defaults, and bad values refused naming file and key.
#include "display_node.hpp"

#include <gtest/gtest.h>

namespace quad::display {
namespace {

TEST(DisplayConfig, TheShippedFileIsReadAndBadValuesAreRefusedNamingFileAndKey)
{
  const DisplayNodeConfig c = displayConfigFrom(common::loadParams(QUAD_CONFIG_DIR "/display.yaml", displayNodeSchema()));
  EXPECT_TRUE(c.world_file.empty());
  EXPECT_EQ(c.state_source, runtime::StateSource::kEstimate);
  EXPECT_DOUBLE_EQ(c.trace.spacing, 0.05);
  EXPECT_EQ(c.trace.max_poses, 20000U);
  for (const auto& [yaml, key] : {std::pair{"trajectory:\n  max_poses: 1\n", "d.yaml:trajectory.max_poses: 1"},
                                  std::pair{"map:\n  rate: 0\n", "d.yaml:map.rate: 0"},
                                  std::pair{"state:\n  source: guess\n", "d.yaml:state.source: guess"},
                                  std::pair{"colour: red\n", "d.yaml:colour"}}) {
    try {
      displayConfigFrom(common::parseParams(yaml, "d.yaml", displayNodeSchema()));
      ADD_FAILURE() << "accepted: " << yaml;
    } catch (const common::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace quad::display
