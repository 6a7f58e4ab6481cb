// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// One logging setup for every quad process: a coloured console sink and one file per module.
///
/// The level comes from the module's config (`log.level`) unless the environment variable
/// QUAD_LOG_LEVEL overrides it; the file goes to QUAD_LOG_DIR (the launcher points every
/// module of a run at one folder), else to the directory given in the options.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <spdlog/logger.h>

#include "quad/common/params.hpp"

namespace quad::common {

/// The environment variables that override a module's log options, declared once.
inline constexpr const char* kLogLevelVariable = "QUAD_LOG_LEVEL";
inline constexpr const char* kLogDirVariable = "QUAD_LOG_DIR";

struct LogOptions {
  std::string level = "info";  ///< trace, debug, info, warn, error, critical, off
  /// Folder of the log file; none: console only (unless QUAD_LOG_DIR is set).
  std::optional<std::filesystem::path> directory;
};

/// Declares `log.level` and `log.directory` in a module's schema.
void addLoggingParams(ParamSchema& schema);

/// Reads the options declared by addLoggingParams.
LogOptions logOptionsFrom(const Params& params);

/// Creates the module's logger, makes it spdlog's default and returns it.
/// Throws std::runtime_error naming the variable or path when the level or folder is bad.
std::shared_ptr<spdlog::logger> setupLogging(std::string_view module_name,
                                             const LogOptions& options = {});

}  // namespace quad::common
