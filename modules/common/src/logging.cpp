// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/logging.hpp"

#include <cstdlib>
#include <stdexcept>
#include <vector>

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "quad/common/param_table.hpp"

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

namespace {

/// The log keys as a module's config writes them.
struct LogParams {
  std::string level = "info";
  std::string directory;  ///< empty: console only
};

const ParamTable<LogParams>& logTable()
{
  static const ParamTable<LogParams> table = [] {
    ParamTable<LogParams> t;
    t.text("log.level", [](LogParams& p) -> std::string& { return p.level; }, kLevels,
           "Log level; QUAD_LOG_LEVEL overrides it")
        .text("log.directory", [](LogParams& p) -> std::string& { return p.directory; }, {},
              "Folder for <module>.log; empty: console only. QUAD_LOG_DIR overrides it");
    return t;
  }();
  return table;
}

}  // namespace

void addLoggingParams(ParamSchema& schema)
{
  for (const ParamSpec& spec : logTable().schema().specs()) {
    schema.add(spec);
  }
}

LogOptions logOptionsFrom(const Params& params)
{
  const LogParams p = logTable().read(params);
  LogOptions options;
  options.level = p.level;
  if (!p.directory.empty()) {
    options.directory = p.directory;
  }
  return options;
}

std::shared_ptr<spdlog::logger> setupLogging(std::string_view module_name, const LogOptions& options)
{
  auto level = parseLevel(options.level, "log.level");
  if (const char* env = std::getenv(kLogLevelVariable); env != nullptr && *env != '\0') {
    level = parseLevel(env, kLogLevelVariable);
  }
  std::optional<std::filesystem::path> directory = options.directory;
  if (const char* env = std::getenv(kLogDirVariable); env != nullptr && *env != '\0') {
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
