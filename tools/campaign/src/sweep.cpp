// SPDX-License-Identifier: BSD-3-Clause
#include "quad/campaign/sweep.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <iterator>
#include <optional>
#include <set>
#include <span>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "quad/common/digest.hpp"
#include "quad/common/params.hpp"
#include "quad/common/yaml_input.hpp"

namespace quad::campaign {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kWorldPrefix = "world:";

std::optional<long> wholeNumber(const std::string& text)
{
  long v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  return ec == std::errc() && end == text.data() + text.size() ? std::optional<long>(v) : std::nullopt;
}

/// The longest run folder name kept whole: file systems hold 255 bytes a name, and a campaign
/// with many axes names its cells past that.
constexpr std::size_t kLongestName = 160;
/// What ends a cut name: a dash and the whole name's digest in 16 hexadecimal digits.
constexpr std::size_t kDigestSuffix = 17;

/// `name` when it is short enough, else its first part and the digest of the whole (still unique).
std::string shortened(const std::string& name)
{
  if (name.size() <= kLongestName) {
    return name;
  }
  const std::uint64_t whole = common::digest(std::as_bytes(std::span(name.data(), name.size())));
  return fmt::format("{}-{:016x}", name.substr(0, kLongestName - kDigestSuffix), whole);
}

/// A folder name's piece: letters, digits, '.', '_' and '-' kept, anything else '_'.
std::string folderSafe(const std::string& text)
{
  std::string out = text;
  std::replace_if(out.begin(), out.end(), [](char c) {
    return !(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-');
  }, '_');
  return out;
}

}  // namespace

std::pair<std::string, std::string> Axis::generatorKey() const
{
  const std::string rest = key.substr(kWorldPrefix.size());
  const auto dot = rest.find('.');
  return {rest.substr(0, dot), dot == std::string::npos ? std::string() : rest.substr(dot + 1)};
}

std::string Axis::shortName() const
{
  const auto cut = key.find_last_of(".:");
  return cut == std::string::npos ? key : key.substr(cut + 1);
}

std::vector<std::string> axisLabels(const std::vector<Axis>& axes)
{
  std::vector<std::string> labels;
  for (const Axis& a : axes) {
    const std::string name = a.shortName();
    const bool shared = name == "seed" || std::count_if(axes.begin(), axes.end(), [&](const Axis& b) {
                                            return b.shortName() == name;
                                          }) > 1;
    labels.push_back(shared ? folderSafe(a.isWorld() ? a.key.substr(kWorldPrefix.size()) : a.key) : name);
  }
  return labels;
}

std::vector<std::string> axisValues(const std::string& text, const std::string& origin)
{
  std::vector<std::string> values;
  if (const auto dots = text.find(".."); dots != std::string::npos) {
    const auto from = wholeNumber(text.substr(0, dots));
    const auto to = wholeNumber(text.substr(dots + 2));
    if (!from || !to || *to < *from || *to - *from >= 10000) {
      throw common::ConfigError({origin + ": " + text + ": expected a range of whole numbers FROM..TO (1..10)"});
    }
    for (long v = *from; v <= *to; ++v) {
      values.push_back(std::to_string(v));
    }
    return values;
  }
  std::size_t start = 0;
  while (start <= text.size()) {
    const auto comma = std::min(text.find(',', start), text.size());
    const std::string value = text.substr(start, comma - start);
    if (value.empty()) {
      throw common::ConfigError({origin + ": " + text + ": an empty value (values are separated by commas)"});
    }
    values.push_back(value);
    start = comma + 1;
  }
  return values;
}

Axis parseAxis(const std::string& text, const std::string& origin)
{
  const auto equals = text.find('=');
  const auto colon = text.find(':');
  if (equals == std::string::npos || colon == std::string::npos || colon == 0 || colon + 1 >= equals) {
    throw common::ConfigError({origin + ": " + text +
                               ": expected MODULE:KEY=V1,V2,... or world:TYPE.KEY=V1,V2,... (FROM..TO for whole numbers)"});
  }
  Axis axis{text.substr(0, equals), axisValues(text.substr(equals + 1), origin + " " + text.substr(0, equals))};
  if (axis.isWorld() && (axis.generatorKey().first.empty() || axis.generatorKey().second.empty())) {
    throw common::ConfigError({origin + ": " + text + ": a world axis is world:TYPE.KEY (world:forest.density)"});
  }
  return axis;
}

std::vector<std::string> PlannedRun::moduleSets() const
{
  std::vector<std::string> sets;
  for (const auto& [k, v] : params) {
    if (!k.starts_with(kWorldPrefix)) {
      sets.push_back(k + "=" + v);
    }
  }
  return sets;
}

std::vector<std::pair<std::string, std::string>> PlannedRun::worldParams() const
{
  std::vector<std::pair<std::string, std::string>> out;
  std::copy_if(params.begin(), params.end(), std::back_inserter(out),
               [](const auto& kv) { return kv.first.starts_with(kWorldPrefix); });
  return out;
}

std::vector<PlannedRun> planRuns(const std::vector<fs::path>& worlds, const std::vector<Axis>& axes, int seeds)
{
  std::set<std::string> keys;
  for (const Axis& a : axes) {
    if (a.values.empty()) {
      throw common::ConfigError({"axis " + a.key + ": no values"});
    }
    if (!keys.insert(a.key).second) {
      throw common::ConfigError({"axis " + a.key + ": named twice"});
    }
  }
  const std::vector<std::string> labels = axisLabels(axes);
  std::vector<PlannedRun> runs;
  std::vector<std::size_t> at(axes.size(), 0);  // an odometer over the axes' values
  for (const fs::path& world : worlds) {
    std::fill(at.begin(), at.end(), 0);
    for (bool more = true; more;) {
      for (int seed = 1; seed <= seeds; ++seed) {
        PlannedRun r;
        r.world = world;
        r.seed = static_cast<std::uint64_t>(seed);
        r.name = world.stem().string();
        for (std::size_t i = 0; i < axes.size(); ++i) {
          r.params.emplace_back(axes[i].key, axes[i].values[at[i]]);
          r.name += "-" + labels[i] + folderSafe(axes[i].values[at[i]]);
        }
        r.name = shortened(r.name + fmt::format("-seed{}", seed));
        runs.push_back(std::move(r));
      }
      more = false;
      for (std::size_t i = axes.size(); i-- > 0;) {
        if (++at[i] < axes[i].values.size()) {
          more = true;
          break;
        }
        at[i] = 0;
      }
    }
  }
  // Two worlds of the same name in different folders would share folders.
  std::set<std::string> names;
  for (const PlannedRun& r : runs) {
    if (!names.insert(r.name).second) {
      throw common::ConfigError({r.world.string() + ": a second world named " + r.world.stem().string() +
                                 " (each run's folder is named after its world)"});
    }
  }
  return runs;
}

std::string worldVariant(const fs::path& world, const std::vector<std::pair<std::string, std::string>>& world_params)
{
  YAML::Node root = common::parseYaml(common::readTextFile(world), world.string());
  YAML::Node generators = root["generators"];
  for (const auto& [key, value] : world_params) {
    const Axis axis{key, {value}};
    const auto [type, param] = axis.generatorKey();
    bool found = false;
    for (std::size_t i = 0; generators && generators.IsSequence() && i < generators.size(); ++i) {
      YAML::Node g = generators[i];
      if (g.IsMap() && g["type"] && g["type"].IsScalar() && g["type"].as<std::string>() == type) {
        g[param] = YAML::Load(value);
        found = true;
      }
    }
    if (!found) {
      throw common::ConfigError({world.string() + ":generators: " + key + "=" + value + ": the world has no " + type +
                                 " generator"});
    }
  }
  // The variant is written into the run's folder: its scans are found where the world's are.
  YAML::Node maps = root["maps"];
  for (std::size_t i = 0; maps && maps.IsSequence() && i < maps.size(); ++i) {
    YAML::Node file = maps[i]["file"];
    if (maps[i].IsMap() && file && file.IsScalar() && fs::path(file.Scalar()).is_relative()) {
      maps[i]["file"] = fs::absolute(world.parent_path() / file.Scalar()).lexically_normal().string();
    }
  }
  YAML::Emitter out;
  out << root;
  return std::string(out.c_str()) + "\n";
}

}  // namespace quad::campaign
