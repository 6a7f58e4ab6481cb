// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target: the MCAP reader (quad bag info, recover, replay). Whatever the bytes, it
// returns what it read or throws BagError naming the byte; never a crash, never an
// allocation the file's claims alone decide. The first byte picks strict or tolerant
// reading; the rest is the file. Seeds: small recordings, plain and zstd, written here.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <span>
#include <unistd.h>

#include "harness.hpp"
#include "quad/bag/mcap.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0) {
    return 0;
  }
  try {
    (void)quad::bag::readMcap(std::span<const std::uint8_t>(data + 1, size - 1), "fuzz.mcap", (data[0] & 1U) != 0);
  } catch (const quad::bag::BagError&) {
    // refused with the byte and the reason: what a bad file must get
  }
  return 0;
}

std::vector<std::string> quad::fuzz::seeds()
{
  namespace fs = std::filesystem;
  std::vector<std::string> out;
  for (const char* compression : {"", "zstd"}) {
    const fs::path file = fs::temp_directory_path() / ("quad_fuzz_seed_" + std::to_string(::getpid()) + ".mcap");
    {
      quad::bag::McapWriter w(file, 256, compression);
      const auto schema = w.addSchema("quad::msg::Goal", "omgidl", "struct Goal { unsigned long goal_id; };");
      const auto channel = w.addChannel(schema, "quad/planning/goal", "cdr", {{"qos", "latched"}});
      for (std::uint32_t i = 1; i <= 20; ++i) {
        const std::vector<std::uint8_t> cdr = {0, 1, 0, 0, static_cast<std::uint8_t>(i), 0, 0, 0};
        w.write(channel, i, i * 1000, i * 1000, cdr.data(), cdr.size());
      }
      w.addMetadata("run", {{"manifest", "demo.yaml"}});
      w.close();
    }
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    fs::remove(file);
    out.push_back(std::string(1, '\0') + bytes);
    out.push_back(std::string(1, '\1') + bytes.substr(0, bytes.size() * 2 / 3));  // cut short, read tolerantly
  }
  return out;
}
