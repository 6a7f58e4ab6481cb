// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// quad's manual pages and bash completion, generated from its command-line definitions
/// (`quad --write-manual DIR`, run by the build), so that they cannot drift from them.

#include <filesystem>
#include <string_view>

namespace CLI {
class App;
}

namespace quad::tools {

/// Writes quad.1 and one page per subcommand (quad-topic-list.1, ...) in roff, and quad.bash
/// (the completion of every subcommand and option), into `dir`; returns how many pages.
int writeManual(CLI::App& app, const std::filesystem::path& dir, std::string_view version);

}  // namespace quad::tools
