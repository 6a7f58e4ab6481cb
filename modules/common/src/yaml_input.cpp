// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/yaml_input.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "quad/common/params.hpp"

namespace quad::common {

std::string yamlText(const YAML::Node& node)
{
  if (!node.IsDefined() || node.IsNull()) {
    return "(missing)";
  }
  if (node.IsScalar()) {
    return node.Scalar();
  }
  YAML::Node flow = YAML::Clone(node);
  flow.SetStyle(YAML::EmitterStyle::Flow);
  YAML::Emitter out;
  out << flow;
  return out.c_str();
}

std::string readTextFile(const std::filesystem::path& file)
{
  std::ifstream in(file);
  if (!in) {
    throw ConfigError({file.string() + ": cannot open: " + std::strerror(errno)});
  }
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

YAML::Node parseYaml(std::string_view text, std::string_view origin)
{
  try {
    return YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    throw ConfigError({std::string(origin) + ":(line " + std::to_string(e.mark.line + 1) + "): (yaml): " + e.msg});
  }
}

void YamlReader::problem(const std::string& key, const YAML::Node& node, const std::string& why)
{
  problems_.push_back(origin_ + ":" + key + ": " + yamlText(node) + ": " + why);
}

void YamlReader::throwIfAny()
{
  if (!problems_.empty()) {
    throw ConfigError(std::move(problems_));
  }
}

void YamlReader::onlyKeys(const YAML::Node& map, const std::string& prefix, const std::set<std::string>& allowed)
{
  for (const auto& entry : map) {
    const std::string key = entry.first.Scalar();
    if (!allowed.contains(key)) {
      std::string list;
      for (const auto& a : allowed) {
        list += (list.empty() ? "" : ", ") + a;
      }
      problem(prefix + key, entry.second, "unknown key (expected one of: " + list + ")");
    }
  }
}

std::optional<double> YamlReader::number(const YAML::Node& node, const std::string& key,
                                         std::optional<double> fallback, double lo, double hi)
{
  if (!node.IsDefined() || node.IsNull()) {
    if (!fallback) {
      problem(key, node, "required");
    }
    return fallback;
  }
  double v = 0.0;
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, v)) {
    problem(key, node, "expected a number");
    return std::nullopt;
  }
  if (!std::isfinite(v)) {
    problem(key, node, "not a finite number");
    return std::nullopt;
  }
  if (v < lo || v > hi) {
    problem(key, node, "out of range [" + formatValue(lo) + ", " + formatValue(hi) + "]");
    return std::nullopt;
  }
  return v;
}

std::optional<bool> YamlReader::flag(const YAML::Node& node, const std::string& key, std::optional<bool> fallback)
{
  if (!node.IsDefined()) {
    if (!fallback) {
      problem(key, node, "required");
    }
    return fallback;
  }
  const std::string v = node.IsScalar() ? node.Scalar() : "";
  if (v != "true" && v != "false") {
    problem(key, node, "expected bool (true or false)");
    return std::nullopt;
  }
  return v == "true";
}

std::optional<std::vector<double>> YamlReader::numbers(const YAML::Node& node, const std::string& key,
                                                       std::size_t count, double lo, double hi)
{
  if (!node.IsDefined() || node.IsNull()) {
    problem(key, node, "required");
    return std::nullopt;
  }
  if (!node.IsSequence() || node.size() != count) {
    problem(key, node, "expected a list of " + std::to_string(count) + " numbers");
    return std::nullopt;
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < count; ++i) {
    const auto v = number(node[i], key + "[" + std::to_string(i) + "]", std::nullopt, lo, hi);
    if (!v) {
      return std::nullopt;
    }
    out.push_back(*v);
  }
  return out;
}

std::optional<std::pair<double, double>> YamlReader::range(const YAML::Node& node, const std::string& key,
                                                           double lo_limit, double hi_limit)
{
  const auto v = numbers(node, key, 2, lo_limit, hi_limit);
  if (!v) {
    return std::nullopt;
  }
  if ((*v)[0] > (*v)[1]) {
    problem(key, node, "expected [low, high] with low <= high");
    return std::nullopt;
  }
  return std::pair((*v)[0], (*v)[1]);
}

std::optional<std::string> YamlReader::text(const YAML::Node& node, const std::string& key,
                                            std::optional<std::string> fallback)
{
  if (!node) {
    if (!fallback) {
      problem(key, node, "required key not set");
    }
    return fallback;
  }
  if (!node.IsScalar()) {
    problem(key, node, "expected a string");
    return std::nullopt;
  }
  return node.as<std::string>();
}

std::vector<std::pair<std::string, std::string>> YamlReader::scalars(const YAML::Node& node, const std::string& key)
{
  std::vector<std::pair<std::string, std::string>> out;
  if (!node) {
    return out;
  }
  if (!node.IsMap()) {
    problem(key, node, "expected a map");
    return out;
  }
  for (const auto& kv : node) {
    const auto k = kv.first.as<std::string>();
    if (auto v = text(kv.second, key + "." + k, std::nullopt)) {
      out.emplace_back(k, *v);
    }
  }
  return out;
}

}  // namespace quad::common
