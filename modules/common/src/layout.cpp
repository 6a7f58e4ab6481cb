// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/layout.hpp"

#include <system_error>

namespace quad::common {

namespace fs = std::filesystem;

Layout layoutOf(const fs::path& exe, const fs::path& source_dir)
{
  const fs::path dir = exe.parent_path();
  // P/bin/<program> or P/lib/quad/<program>
  const fs::path prefix = dir.filename() == "quad" && dir.parent_path().filename() == "lib"
                              ? dir.parent_path().parent_path()
                              : dir.parent_path();
  std::error_code ec;
  if (fs::is_directory(prefix / "share" / "quad" / "configs", ec)) {
    return {true, prefix / "share" / "quad", prefix};
  }
  // A build tree: <build>/tools/quad/quad or <build>/modules/<m>/node/<program>; the build's
  // top is the first folder above that holds CMakeCache.txt.
  fs::path build = dir;
  while (!build.empty() && build != build.root_path() && !fs::exists(build / "CMakeCache.txt", ec)) {
    build = build.parent_path();
  }
  return {false, source_dir, build.empty() || build == build.root_path() ? dir : build};
}

const Layout& layout()
{
  static const Layout kLayout = [] {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    return layoutOf(ec ? fs::current_path() / "quad" : self, QUAD_SOURCE_DIR);
  }();
  return kLayout;
}

fs::path configDir() { return layout().data / "configs"; }

fs::path programPath(const Layout& layout, std::string_view build_path)
{
  if (!layout.installed) {
    return layout.programs / build_path;
  }
  const fs::path name = fs::path(build_path).filename();
  return name == "quad" ? layout.programs / "bin" / name : layout.programs / "lib" / "quad" / name;
}

}  // namespace quad::common
