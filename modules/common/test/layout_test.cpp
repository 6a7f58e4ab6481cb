// SPDX-License-Identifier: BSD-3-Clause
// Where programs and data are: an installed prefix told from a build tree by what is there.
#include "quad/common/layout.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

namespace quad::common {
namespace {

namespace fs = std::filesystem;

class LayoutTest : public ::testing::Test {
protected:
  void SetUp() override
  {
    root_ = fs::temp_directory_path() / ("quad_layout_test_" + std::to_string(::getpid()));
    fs::remove_all(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path touch(const fs::path& relative)
  {
    const fs::path p = root_ / relative;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << "";
    return p;
  }
  fs::path root_;
};

TEST_F(LayoutTest, AProgramInBinOrLibQuadBesideShareQuadIsInstalled)
{
  fs::create_directories(root_ / "p/share/quad/configs");
  for (const char* program : {"p/bin/quad", "p/lib/quad/quad_plant_node"}) {
    const Layout l = layoutOf(touch(program), "/src");
    EXPECT_TRUE(l.installed) << program;
    EXPECT_EQ(l.data, root_ / "p/share/quad") << program;
    EXPECT_EQ(configDir(), layout().data / "configs");
    EXPECT_EQ(programPath(l, "modules/plant/node/quad_plant_node"), root_ / "p/lib/quad/quad_plant_node");
    EXPECT_EQ(programPath(l, "tools/quad/quad"), root_ / "p/bin/quad");
  }
}

TEST_F(LayoutTest, AProgramInABuildTreeFindsTheBuildsTopAndTheSources)
{
  touch("build/CMakeCache.txt");
  for (const char* program : {"build/tools/quad/quad", "build/modules/plant/node/quad_plant_node"}) {
    const Layout l = layoutOf(touch(program), "/src");
    EXPECT_FALSE(l.installed) << program;
    EXPECT_EQ(l.data, "/src") << program;
    EXPECT_EQ(l.programs, root_ / "build") << program;
    EXPECT_EQ(programPath(l, "tools/quad/quad"), root_ / "build/tools/quad/quad");
  }
}

TEST_F(LayoutTest, ABinFolderWithoutShareQuadIsNotTakenForAnInstallation)
{
  touch("usr/share/other/configs/x");
  const Layout l = layoutOf(touch("usr/bin/quad"), "/src");
  EXPECT_FALSE(l.installed);
  EXPECT_EQ(l.data, "/src");
}

}  // namespace
}  // namespace quad::common
