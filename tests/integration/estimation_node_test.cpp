// SPDX-License-Identifier: BSD-3-Clause
// The estimation node on the plant's sensors: aligned on the ground, it publishes a healthy,
// aided state where the vehicle stands.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "module_wait.hpp"
#include "process.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;

std::map<std::string, std::string> env(int domain)
{
  return {{"QUAD_DOMAIN_ID", std::to_string(domain)}, {"QUAD_TRANSPORT", "udp"}};
}

double norm(const nlohmann::json& v) { return std::sqrt(std::pow(v["x"].get<double>(), 2) + std::pow(v["y"].get<double>(), 2) + std::pow(v["z"].get<double>(), 2)); }

TEST(EstimationNode, OnTheGroundItAlignsAndPublishesAHealthyAidedStateWhereTheVehicleStands)
{
  const int domain = 118;
  const auto dir = std::filesystem::temp_directory_path() / "quad_estimation_node_test";
  std::filesystem::create_directories(dir);
  // GIVEN the plant in real time with the vehicle on the ground at the demo world's start
  // (0, 0, 0), level, facing x, and the estimator
  std::ofstream(dir / "plant.yaml") << "vehicle: " << QUAD_CONFIG_DIR << "/vehicles/x500.yaml\nworld: " << QUAD_CONFIG_DIR
                                    << "/worlds/demo.yaml\nsim: {mode: realtime, duration: 8}\n";
  ChildProcess estimation({QUAD_ESTIMATION_NODE, "--config", QUAD_CONFIG_DIR "/estimation.yaml"}, env(domain));
  ASSERT_TRUE(quad::test::waitForRunningModule(domain, "estimation", 20s)) << estimation.output();
  ChildProcess plant({QUAD_PLANT_NODE, "--config", (dir / "plant.yaml").string()}, env(domain));
  // WHEN it has fused 5 s of sensors
  std::this_thread::sleep_for(5s);
  ChildProcess echo({QUAD_TOOL, "topic", "echo", "quad/estimation/state", "-n", "1", "--json", "--timeout", "10"},
                    env(domain));
  ASSERT_EQ(echo.wait(20s), 0) << echo.output();
  ASSERT_EQ(plant.wait(30s), 0) << plant.output();
  // THEN the state is aligned, fed, aided and confident, and where the vehicle stands: within
  // 10 cm (the fixes' 2 cm, with the barometer and the IMU), level and facing x within 2°
  // (at rest the accelerometer's turn-on bias and the tilt trade, and the field's dip turns
  // a tilt error into a yaw error twice its size)
  std::istringstream lines(echo.output());
  std::string line;
  std::getline(lines, line);
  const auto s = nlohmann::json::parse(line);
  EXPECT_TRUE(s["aligned"].get<bool>());
  EXPECT_TRUE(s["imu_ok"].get<bool>());
  EXPECT_TRUE(s["position_aided"].get<bool>());
  EXPECT_TRUE(s["heading_aided"].get<bool>());
  EXPECT_TRUE(s["covariance_ok"].get<bool>());
  EXPECT_LT(norm(s["p_W"]), 0.1) << line;
  EXPECT_LT(norm(s["p_std"]), 0.05) << line;
  const auto& q = s["q_WB"];
  const double angle = 2.0 * std::acos(std::min(1.0, std::abs(q["w"].get<double>())));
  EXPECT_LT(angle, 2.0 * M_PI / 180) << line;
  EXPECT_EQ(s["position_rejected"].get<std::uint64_t>(), 0U);
}

}  // namespace
