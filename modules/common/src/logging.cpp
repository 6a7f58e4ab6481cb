#include "quad/common/logging.hpp"

#include <cstdlib>
#include <stdexcept>
#include <vector>

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

namespace quad::common {
namespace {

const std::vector<std::string> kLevels{"trace", "debug", "info", "warn", "error", "critical", "off"};

spdlog::level::level_enum parseLevel(const std::string& text, std::string_view source)
{
  for (const auto& name : kLevels) {
    if (name == text) {
      return spdlog::level::from_str(text);
    }
  }
  throw std::runtime_error(std::string(source) + ": " + text +
                           ": not a log level (trace, debug, info, warn, error, critical, off)");
}

}  // namespace

void addLoggingParams(ParamSchema& schema)
{
  schema.addString("log.level", "info", kLevels, "Log level; QUAD_LOG_LEVEL overrides it");
  schema.addString("log.directory", "", {},
                   "Folder for <module>.log; empty: console only. QUAD_LOG_DIR overrides it");
}

LogOptions logOptionsFrom(const Params& params)
{
  LogOptions options;
  options.level = params.getString("log.level");
  if (const auto& dir = params.getString("log.directory"); !dir.empty()) {
    options.directory = dir;
  }
  return options;
}

std::shared_ptr<spdlog::logger> setupLogging(std::string_view module_name, const LogOptions& options)
{
  auto level = parseLevel(options.level, "log.level");
  if (const char* env = std::getenv("QUAD_LOG_LEVEL"); env != nullptr && *env != '\0') {
    level = parseLevel(env, "QUAD_LOG_LEVEL");
  }
  std::optional<std::filesystem::path> directory = options.directory;
  if (const char* env = std::getenv("QUAD_LOG_DIR"); env != nullptr && *env != '\0') {
    directory = env;
  }

  std::vector<spdlog::sink_ptr> sinks;
  sinks.push_back(std::make_shared<spdlog::sinks::stderr_color_sink_mt>());
  if (directory) {
    std::error_code ec;
    std::filesystem::create_directories(*directory, ec);
    if (ec) {
      throw std::runtime_error("log directory " + directory->string() + ": " + ec.message());
    }
    const auto file = *directory / (std::string(module_name) + ".log");
    sinks.push_back(std::make_shared<spdlog::sinks::basic_file_sink_mt>(file.string()));
  }
  auto logger = std::make_shared<spdlog::logger>(std::string(module_name), sinks.begin(), sinks.end());
  logger->set_level(level);
  logger->set_pattern("%Y-%m-%dT%H:%M:%S.%e %^%l%$ [%n] %v");
  logger->flush_on(spdlog::level::warn);
  spdlog::set_default_logger(logger);
  return logger;
}

}  // namespace quad::common
