// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Where quad's programs and data files are, found from the running program's own place, so
/// that a build tree and an installed prefix both work and a prefix can move:
/// - **installed** (`cmake --install`, the .deb): `P/bin/quad`, the module programs in
///   `P/lib/quad/`, and `configs/`, `bringup/` and `idl/` under `P/share/quad/`. A program in
///   `P/bin` or `P/lib/quad` whose prefix holds `share/quad/configs` is installed.
/// - **build tree**: the programs where the build put them, the data in the source tree the
///   build was configured from.

#include <filesystem>
#include <string_view>

namespace quad::common {

struct Layout {
  bool installed = false;
  std::filesystem::path data;      ///< holds configs/, bringup/, idl/: P/share/quad or the source tree
  std::filesystem::path programs;  ///< P (installed) or the build tree
};

/// The layout of the running program (worked out once).
const Layout& layout();

/// The layout a program at `exe` belongs to; `source_dir` is the source tree of a build.
Layout layoutOf(const std::filesystem::path& exe, const std::filesystem::path& source_dir);

/// configs/ of the layout: where relative paths in configs resolve, and the QoS file.
std::filesystem::path configDir();

/// A quad program by its place in the build tree ("modules/plant/node/quad_plant_node",
/// "tools/quad/quad"); installed, `quad` is in P/bin and every other in P/lib/quad.
std::filesystem::path programPath(const Layout& layout, std::string_view build_path);

}  // namespace quad::common
