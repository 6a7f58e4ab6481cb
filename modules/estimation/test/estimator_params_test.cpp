// SPDX-License-Identifier: BSD-3-Clause
// configs/estimation.yaml: read with its defaults, and bad values refused naming file and key.
#include "quad/estimation/estimator_params.hpp"

#include <gtest/gtest.h>

namespace quad::estimation {
namespace {

TEST(EstimatorParams, TheShippedFileIsReadAndBadValuesAreRefusedNamingFileAndKey)
{
  const EstimatorParams p = estimatorParamsOf(common::loadParams(QUAD_CONFIG_DIR "/estimation.yaml", estimatorSchema()));
  EXPECT_DOUBLE_EQ(p.gate_probability, 0.999);
  EXPECT_EQ(p.mag_field_W, Vector3(0.0, 21.0, -43.0));
  try {
    estimatorParamsOf(common::parseParams("gate:\n  probability: 2\n", "e.yaml", estimatorSchema()));
    FAIL() << "accepted";
  } catch (const common::ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("e.yaml:gate.probability: 2"), std::string::npos) << what;
  }
  try {
    estimatorParamsOf(common::parseParams("mag:\n  field: [0.1, 0, -43]\n", "e.yaml", estimatorSchema()));
    FAIL() << "accepted";
  } catch (const common::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("e.yaml:mag.field"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace quad::estimation
