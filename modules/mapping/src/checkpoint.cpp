// SPDX-License-Identifier: BSD-3-Clause
#include "quad/mapping/checkpoint.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace quad::mapping {

namespace {
constexpr char kMagic[8] = {'Q', 'U', 'A', 'D', 'M', 'A', 'P', '1'};

template <class T>
void put(std::ostream& out, T value)
{
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.write(bytes, sizeof(T));
}

template <class T>
bool get(std::istream& in, T& value)
{
  char bytes[sizeof(T)];
  if (!in.read(bytes, sizeof(T))) {
    return false;
  }
  std::memcpy(&value, bytes, sizeof(T));
  return true;
}
}  // namespace

void writeCheckpoint(const std::filesystem::path& file, const Mapper& mapper, const MapCheckpoint& meta)
{
  writeCheckpoint(file, mapper.resolution(), mapper.image(true).data, meta);
}

void writeCheckpoint(const std::filesystem::path& file, double resolution, const std::vector<std::uint8_t>& tree_data,
                     const MapCheckpoint& meta)
{
  std::filesystem::path tmp = file;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(kMagic, sizeof(kMagic));
    put(out, resolution);
    put(out, meta.next_update_seq);
    put(out, meta.stamp_ns);
    out.write(reinterpret_cast<const char*>(tree_data.data()), static_cast<std::streamsize>(tree_data.size()));
    out.flush();
    if (!out) {
      throw std::runtime_error(tmp.string() + ": cannot write the map checkpoint");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    throw std::runtime_error(fmt::format("{}: cannot replace it with {}: {}", file.string(), tmp.string(), ec.message()));
  }
}

std::optional<MapCheckpoint> readCheckpoint(const std::filesystem::path& file, Mapper& mapper)
{
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    if (!std::filesystem::exists(file)) {
      return std::nullopt;
    }
    throw std::runtime_error(file.string() + ": cannot read the map checkpoint");
  }
  char magic[sizeof(kMagic)];
  if (!in.read(magic, sizeof(magic)) || std::memcmp(magic, kMagic, sizeof(kMagic)) != 0) {
    throw std::runtime_error(file.string() + ": not a quad map checkpoint");
  }
  double resolution = 0.0;
  MapCheckpoint meta;
  if (!get(in, resolution) || !get(in, meta.next_update_seq) || !get(in, meta.stamp_ns)) {
    throw std::runtime_error(file.string() + ": map checkpoint cut short");
  }
  if (!(std::abs(resolution - mapper.resolution()) <= 1e-9)) {
    throw std::runtime_error(fmt::format("{}: a map of resolution {} m; the mapper's is {} m", file.string(),
                                         resolution, mapper.resolution()));
  }
  if (meta.next_update_seq == 0) {
    throw std::runtime_error(file.string() + ": next update number 0 (numbers start at 1)");
  }
  if (!mapper.readTree(in)) {
    throw std::runtime_error(file.string() + ": the octree in the map checkpoint is cut short or damaged");
  }
  return meta;
}

}  // namespace quad::mapping
