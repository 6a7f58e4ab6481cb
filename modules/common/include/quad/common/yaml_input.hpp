// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Reading YAML from outside (configs, worlds, fault schedules) with every problem reported
/// as `origin:key: value: reason`, the one format of quad's configuration errors.

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace quad::common {

/// A node as it was written: a scalar's text, anything else in flow style, "(missing)".
std::string yamlText(const YAML::Node& node);

/// The text of a file; throws ConfigError `file: cannot open: reason`.
std::string readTextFile(const std::filesystem::path& file);

/// Parses YAML; a syntax error is a ConfigError `origin:(line N): (yaml): message`.
YAML::Node parseYaml(std::string_view text, std::string_view origin);

/// Collects problems while values are read; throw them together with `throwIfAny()`.
/// Look keys up on non-const YAML::Node values: yaml-cpp makes a missing key of a const node
/// an invalid node that throws when asked anything, where a non-const one reads as undefined.
class YamlReader {
public:
  explicit YamlReader(std::string_view origin) : origin_(origin) {}

  void problem(const std::string& key, const YAML::Node& node, const std::string& why);
  bool ok() const { return problems_.empty(); }
  /// Throws ConfigError with every problem recorded, if any.
  void throwIfAny();

  /// Records an "unknown key" problem for each key of `map` not in `allowed`.
  void onlyKeys(const YAML::Node& map, const std::string& prefix, const std::set<std::string>& allowed);

  /// A finite number in [lo, hi]; `fallback` when absent (absent without one is a problem).
  std::optional<double> number(const YAML::Node& node, const std::string& key,
                               std::optional<double> fallback, double lo, double hi);
  /// true or false; `fallback` when absent (absent without one is a problem).
  std::optional<bool> flag(const YAML::Node& node, const std::string& key, std::optional<bool> fallback);
  /// A list of exactly `count` finite numbers in [lo, hi].
  std::optional<std::vector<double>> numbers(const YAML::Node& node, const std::string& key,
                                             std::size_t count, double lo, double hi);
  /// [low, high] with lo_limit <= low <= high <= hi_limit.
  std::optional<std::pair<double, double>> range(const YAML::Node& node, const std::string& key,
                                                 double lo_limit, double hi_limit);
  /// A scalar as text; `fallback` when absent (absent without one is a problem).
  std::optional<std::string> text(const YAML::Node& node, const std::string& key,
                                  std::optional<std::string> fallback);
  /// A map of scalars, in the order written.
  std::vector<std::pair<std::string, std::string>> scalars(const YAML::Node& node, const std::string& key);

private:
  std::string origin_;
  std::vector<std::string> problems_;
};

}  // namespace quad::common
