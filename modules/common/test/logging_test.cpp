// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/logging.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace quad::common {
namespace {

TEST(Logging, WritesOneFilePerModuleInTheGivenFolder)
{
  const auto dir = std::filesystem::temp_directory_path() / "quad_logging_test";
  std::filesystem::remove_all(dir);
  unsetenv("QUAD_LOG_DIR");
  unsetenv("QUAD_LOG_LEVEL");
  auto logger = setupLogging("probe", LogOptions{.level = "debug", .directory = dir});
  logger->debug("value {}", 42);
  logger->flush();
  std::ifstream in(dir / "probe.log");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("[probe] value 42"), std::string::npos) << text.str();
  std::filesystem::remove_all(dir);
}

TEST(Logging, EnvironmentOverridesTheConfiguredLevel)
{
  unsetenv("QUAD_LOG_DIR");
  setenv("QUAD_LOG_LEVEL", "error", 1);
  auto logger = setupLogging("probe", LogOptions{.level = "debug"});
  EXPECT_EQ(logger->level(), spdlog::level::err);
  unsetenv("QUAD_LOG_LEVEL");
}

TEST(Logging, BadLevelNamesItsSource)
{
  unsetenv("QUAD_LOG_LEVEL");
  EXPECT_THROW(setupLogging("probe", LogOptions{.level = "loud"}), std::runtime_error);
  setenv("QUAD_LOG_LEVEL", "loud", 1);
  try {
    setupLogging("probe", LogOptions{});
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("QUAD_LOG_LEVEL: loud:", 0), 0U) << e.what();
  }
  unsetenv("QUAD_LOG_LEVEL");
}

TEST(Logging, LoggingParamsAreDeclaredWithDefaults)
{
  ParamSchema schema;
  addLoggingParams(schema);
  const LogOptions options = logOptionsFrom(defaultParams(schema));
  EXPECT_EQ(options.level, "info");
  EXPECT_FALSE(options.directory.has_value());
}

}  // namespace
}  // namespace quad::common
