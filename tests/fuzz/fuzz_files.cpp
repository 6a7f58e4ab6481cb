// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target: the readers of files from outside: a vehicle config (the parameter schema
// parser every module config goes through), a world, a launch manifest. The first byte picks
// the reader; the rest is the YAML text. Bad input is an error naming the file and key, never
// a crash. Corpus: configs/vehicles, configs/worlds, bringup (each file prefixed by the
// driver's splices; the seeds below carry the right first byte).
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness.hpp"
#include "quad/launch/manifest.hpp"
#include "quad/common/params.hpp"
#include "quad/world/world_file.hpp"
#include "quad/vehicle/vehicle.hpp"

namespace {

namespace fs = std::filesystem;

void readAs(std::uint8_t reader, const std::string& text)
{
  try {
    switch (reader % 3) {
      case 0:
        (void)quad::common::parseParams(text, "fuzz.yaml", quad::vehicle::vehicleSchema());
        break;
      case 1:
        (void)quad::world::parseWorld(text, "fuzz.yaml");
        break;
      default: {
        const quad::launch::ProgramLookup lookup{{false, QUAD_SOURCE_DIR, QUAD_BUILD_DIR}, {}};
        (void)quad::launch::parseManifest(text, fs::path(QUAD_SOURCE_DIR) / "bringup/fuzz.yaml", {}, lookup);
        break;
      }
    }
  } catch (const std::exception&) {
    // refused with a message: what bad input must get
  }
}

std::string fileText(const fs::path& p)
{
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0) {
    return 0;
  }
  readAs(data[0], std::string(reinterpret_cast<const char*>(data + 1), size - 1));
  return 0;
}

std::vector<std::string> quad::fuzz::seeds()
{
  std::vector<std::string> out;
  const fs::path root = QUAD_SOURCE_DIR;
  for (const auto& [reader, dir] : {std::pair{0, "configs/vehicles"}, std::pair{1, "configs/worlds"},
                                    std::pair{2, "bringup"}}) {
    for (const auto& e : fs::directory_iterator(root / dir)) {
      if (e.path().extension() == ".yaml") {
        out.push_back(std::string(1, static_cast<char>(reader)) + fileText(e.path()));
      }
    }
  }
  return out;
}
