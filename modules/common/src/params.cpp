// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/params.hpp"

#include "quad/common/yaml_input.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace quad::common {
namespace {

std::string joinLines(const std::vector<std::string>& lines)
{
  std::string out;
  for (const auto& line : lines) {
    if (!out.empty()) {
      out += '\n';
    }
    out += line;
  }
  return out;
}

std::string formatNumber(double v)
{
  if (std::isnan(v)) {
    return ".nan";
  }
  if (std::isinf(v)) {
    return v > 0 ? ".inf" : "-.inf";
  }
  // The shortest of 15 or 17 significant digits that reads back as the same double.
  for (const int precision : {15, 17}) {
    std::ostringstream os;
    os.precision(precision);
    os << v;
    if (precision == 17 || std::stod(os.str()) == v) {
      return os.str();
    }
  }
  return {};
}

std::string rangeText(const ParamSpec& spec)
{
  std::string lo = spec.min ? formatNumber(*spec.min) : "-inf";
  std::string hi = spec.max ? formatNumber(*spec.max) : "inf";
  std::string text = "[" + lo + ", " + hi + "]";
  if (!spec.unit.empty()) {
    text += " " + spec.unit;
  }
  return text;
}

std::size_t editDistance(std::string_view a, std::string_view b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) {
    row[j] = j;
  }
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0U : 1U)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string closestKey(const ParamSchema& schema, std::string_view key)
{
  std::string best;
  std::size_t best_distance = 3;  // suggest only near misses
  for (const auto& spec : schema.specs()) {
    const std::size_t d = editDistance(spec.key, key);
    if (d < best_distance) {
      best_distance = d;
      best = spec.key;
    }
  }
  return best;
}

/// Collects problems as `origin:key: value: reason` lines.
class Problems {
public:
  explicit Problems(std::string_view origin) : origin_(origin) {}

  void add(std::string_view key, std::string_view value, std::string_view reason)
  {
    lines_.push_back(origin_ + ":" + std::string(key) + ": " + std::string(value) + ": " +
                     std::string(reason));
  }
  bool empty() const { return lines_.empty(); }
  std::vector<std::string> take() { return std::move(lines_); }

private:
  std::string origin_;
  std::vector<std::string> lines_;
};

/// Checks a number against the spec's range and finiteness; returns the reason or "".
std::string checkNumber(const ParamSpec& spec, double v)
{
  if (!std::isfinite(v)) {
    return "not a finite number";
  }
  if ((spec.min && v < *spec.min) || (spec.max && v > *spec.max)) {
    return "out of range " + rangeText(spec);
  }
  return {};
}

std::optional<double> scalarAsDouble(const YAML::Node& node)
{
  if (!node.IsScalar()) {
    return std::nullopt;
  }
  double v = 0.0;
  if (!YAML::convert<double>::decode(node, v)) {
    return std::nullopt;
  }
  return v;
}

/// Converts one YAML value to the declared type, or records why it cannot.
std::optional<ParamValue> convert(const ParamSpec& spec, const YAML::Node& node, Problems& problems)
{
  const std::string text = yamlText(node);
  const std::string expected = "expected " + std::string(toString(spec.type));
  switch (spec.type) {
    case ParamType::kBool: {
      bool v = false;
      if (!node.IsScalar() || !YAML::convert<bool>::decode(node, v)) {
        problems.add(spec.key, text, expected + " (true or false)");
        return std::nullopt;
      }
      return v;
    }
    case ParamType::kInt: {
      std::int64_t v = 0;
      if (!node.IsScalar() || !YAML::convert<std::int64_t>::decode(node, v)) {
        problems.add(spec.key, text, expected);
        return std::nullopt;
      }
      if (auto reason = checkNumber(spec, static_cast<double>(v)); !reason.empty()) {
        problems.add(spec.key, text, reason);
        return std::nullopt;
      }
      return v;
    }
    case ParamType::kDouble: {
      const auto v = scalarAsDouble(node);
      if (!v) {
        problems.add(spec.key, text, expected);
        return std::nullopt;
      }
      if (auto reason = checkNumber(spec, *v); !reason.empty()) {
        problems.add(spec.key, text, reason);
        return std::nullopt;
      }
      return *v;
    }
    case ParamType::kString: {
      if (!node.IsScalar()) {
        problems.add(spec.key, text, expected);
        return std::nullopt;
      }
      const std::string& v = node.Scalar();
      if (!spec.choices.empty() &&
          std::find(spec.choices.begin(), spec.choices.end(), v) == spec.choices.end()) {
        std::string allowed;
        for (const auto& c : spec.choices) {
          allowed += (allowed.empty() ? "" : ", ") + c;
        }
        problems.add(spec.key, text, "not one of: " + allowed);
        return std::nullopt;
      }
      return v;
    }
    case ParamType::kVector: {
      if (!node.IsSequence() || node.size() == 0) {
        problems.add(spec.key, text, "expected a non-empty list of numbers");
        return std::nullopt;
      }
      if (spec.size != 0 && node.size() != spec.size) {
        problems.add(spec.key, text,
                     "expected " + std::to_string(spec.size) + " numbers, got " +
                         std::to_string(node.size()));
        return std::nullopt;
      }
      std::vector<double> values;
      for (std::size_t i = 0; i < node.size(); ++i) {
        const auto v = scalarAsDouble(node[i]);
        const std::string element_key = spec.key + "[" + std::to_string(i) + "]";
        if (!v) {
          problems.add(element_key, yamlText(node[i]), "expected a number");
          return std::nullopt;
        }
        if (auto reason = checkNumber(spec, *v); !reason.empty()) {
          problems.add(element_key, yamlText(node[i]), reason);
          return std::nullopt;
        }
        values.push_back(*v);
      }
      return values;
    }
  }
  return std::nullopt;
}

/// Flattens nested maps into dotted keys; sequences and scalars are leaves.
/// Keys given without a value are reported here and kept in `given`.
void flatten(const YAML::Node& node, const std::string& prefix,
             std::vector<std::pair<std::string, YAML::Node>>& leaves,
             std::vector<std::string>& given, Problems& problems)
{
  for (const auto& entry : node) {
    const std::string name = entry.first.Scalar();
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    const YAML::Node& value = entry.second;
    if (value.IsMap()) {
      flatten(value, key, leaves, given, problems);
    } else if (value.IsNull()) {
      problems.add(key, "null", "no value given");
      given.push_back(key);
    } else {
      leaves.emplace_back(key, value);
    }
  }
}

bool holdsType(const ParamValue& value, ParamType type)
{
  switch (type) {
    case ParamType::kBool:
      return std::holds_alternative<bool>(value);
    case ParamType::kInt:
      return std::holds_alternative<std::int64_t>(value);
    case ParamType::kDouble:
      return std::holds_alternative<double>(value);
    case ParamType::kString:
      return std::holds_alternative<std::string>(value);
    case ParamType::kVector:
      return std::holds_alternative<std::vector<double>>(value);
  }
  return false;
}

}  // namespace

std::string_view toString(ParamType type)
{
  switch (type) {
    case ParamType::kBool:
      return "bool";
    case ParamType::kInt:
      return "integer";
    case ParamType::kDouble:
      return "number";
    case ParamType::kString:
      return "string";
    case ParamType::kVector:
      return "list of numbers";
  }
  return "?";
}

std::string formatValue(const ParamValue& value)
{
  struct Visitor {
    std::string operator()(bool v) const { return v ? "true" : "false"; }
    std::string operator()(std::int64_t v) const { return std::to_string(v); }
    std::string operator()(double v) const { return formatNumber(v); }
    std::string operator()(const std::string& v) const { return v; }
    std::string operator()(const std::vector<double>& v) const
    {
      std::string out = "[";
      for (std::size_t i = 0; i < v.size(); ++i) {
        out += (i == 0 ? "" : ", ") + formatNumber(v[i]);
      }
      return out + "]";
    }
  };
  return std::visit(Visitor{}, value);
}

ConfigError::ConfigError(std::vector<std::string> problems)
    : std::runtime_error(joinLines(problems)), problems_(std::move(problems))
{
}

ParamSchema& ParamSchema::add(ParamSpec spec)
{
  if (spec.key.empty() || find(spec.key) != nullptr) {
    throw std::logic_error("ParamSchema: empty or duplicate key '" + spec.key + "'");
  }
  if (spec.default_value) {
    if (!holdsType(*spec.default_value, spec.type)) {
      throw std::logic_error("ParamSchema: default of '" + spec.key + "' is not a " +
                             std::string(toString(spec.type)));
    }
    Problems problems("<schema>");
    YAML::Node node = YAML::Load(formatValue(*spec.default_value));
    if (spec.type == ParamType::kString) {
      node = YAML::Node(std::get<std::string>(*spec.default_value));
    }
    convert(spec, node, problems);
    if (!problems.empty()) {
      throw std::logic_error("ParamSchema: default invalid: " + joinLines(problems.take()));
    }
  }
  specs_.push_back(std::move(spec));
  return *this;
}

ParamSchema& ParamSchema::addBool(std::string key, bool default_value, std::string description)
{
  return add({.key = std::move(key), .type = ParamType::kBool, .default_value = default_value,
              .description = std::move(description)});
}

ParamSchema& ParamSchema::addInt(std::string key, std::optional<std::int64_t> default_value,
                                 std::optional<double> min, std::optional<double> max,
                                 std::string unit, std::string description)
{
  ParamSpec spec{.key = std::move(key), .type = ParamType::kInt, .min = min, .max = max,
                 .unit = std::move(unit), .description = std::move(description)};
  if (default_value) {
    spec.default_value = *default_value;
  }
  return add(std::move(spec));
}

ParamSchema& ParamSchema::addDouble(std::string key, std::optional<double> default_value,
                                    std::optional<double> min, std::optional<double> max,
                                    std::string unit, std::string description)
{
  ParamSpec spec{.key = std::move(key), .type = ParamType::kDouble, .min = min, .max = max,
                 .unit = std::move(unit), .description = std::move(description)};
  if (default_value) {
    spec.default_value = *default_value;
  }
  return add(std::move(spec));
}

ParamSchema& ParamSchema::addString(std::string key, std::optional<std::string> default_value,
                                    std::vector<std::string> choices, std::string description)
{
  ParamSpec spec{.key = std::move(key), .type = ParamType::kString,
                 .choices = std::move(choices), .description = std::move(description)};
  if (default_value) {
    spec.default_value = std::move(*default_value);
  }
  return add(std::move(spec));
}

ParamSchema& ParamSchema::addVector(std::string key,
                                    std::optional<std::vector<double>> default_value,
                                    std::size_t size, std::optional<double> min,
                                    std::optional<double> max, std::string unit,
                                    std::string description)
{
  ParamSpec spec{.key = std::move(key), .type = ParamType::kVector, .min = min, .max = max,
                 .size = size, .unit = std::move(unit), .description = std::move(description)};
  if (default_value) {
    spec.default_value = std::move(*default_value);
  }
  return add(std::move(spec));
}

const ParamSpec* ParamSchema::find(std::string_view key) const
{
  const auto it = std::find_if(specs_.begin(), specs_.end(),
                               [key](const ParamSpec& s) { return s.key == key; });
  return it == specs_.end() ? nullptr : &*it;
}

Params::Params(std::map<std::string, ParamValue, std::less<>> values, std::string origin)
    : values_(std::move(values)), origin_(std::move(origin))
{
}

const ParamValue& Params::at(std::string_view key) const
{
  const auto it = values_.find(key);
  if (it == values_.end()) {
    throw std::logic_error("Params: key '" + std::string(key) + "' is not declared in the schema");
  }
  return it->second;
}

namespace {
template <class T>
const T& typed(const ParamValue& value, std::string_view key)
{
  if (const T* v = std::get_if<T>(&value)) {
    return *v;
  }
  throw std::logic_error("Params: key '" + std::string(key) + "' read as the wrong type");
}
}  // namespace

bool Params::getBool(std::string_view key) const { return typed<bool>(at(key), key); }
std::int64_t Params::getInt(std::string_view key) const
{
  return typed<std::int64_t>(at(key), key);
}
double Params::getDouble(std::string_view key) const { return typed<double>(at(key), key); }
const std::string& Params::getString(std::string_view key) const
{
  return typed<std::string>(at(key), key);
}
const std::vector<double>& Params::getVector(std::string_view key) const
{
  return typed<std::vector<double>>(at(key), key);
}

Params parseParams(std::string_view yaml_text, std::string_view origin, const ParamSchema& schema)
{
  Problems problems(origin);
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml_text));
  } catch (const YAML::Exception& e) {
    problems.add("(line " + std::to_string(e.mark.line + 1) + ")", "(yaml)", e.msg);
    throw ConfigError(problems.take());
  }

  std::vector<std::pair<std::string, YAML::Node>> leaves;
  std::vector<std::string> given;
  if (root.IsMap()) {
    flatten(root, "", leaves, given, problems);
  } else if (!root.IsNull()) {
    problems.add("(top level)", yamlText(root), "expected a map of keys to values");
    throw ConfigError(problems.take());
  }
  for (const auto& leaf : leaves) {
    given.push_back(leaf.first);
  }

  std::map<std::string, ParamValue, std::less<>> values;
  for (const auto& [key, node] : leaves) {
    const ParamSpec* spec = schema.find(key);
    if (spec == nullptr) {
      std::string reason = "unknown key";
      if (const auto near = closestKey(schema, key); !near.empty()) {
        reason += " (did you mean '" + near + "'?)";
      }
      problems.add(key, yamlText(node), reason);
      continue;
    }
    if (auto value = convert(*spec, node, problems)) {
      values.emplace(key, std::move(*value));
    }
  }
  for (const auto& spec : schema.specs()) {
    if (values.contains(spec.key)) {
      continue;
    }
    if (std::find(given.begin(), given.end(), spec.key) != given.end()) {
      continue;  // present but invalid: already reported
    }
    if (spec.default_value) {
      values.emplace(spec.key, *spec.default_value);
    } else {
      problems.add(spec.key, "(missing)", "required key not set");
    }
  }
  if (!problems.empty()) {
    throw ConfigError(problems.take());
  }
  return Params(std::move(values), std::string(origin));
}

ParamOverride parseOverride(std::string_view text)
{
  const auto eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0) {
    throw ConfigError({"--set " + std::string(text) + ": expected KEY=VALUE"});
  }
  return {std::string(text.substr(0, eq)), std::string(text.substr(eq + 1))};
}

Params parseParams(std::string_view yaml_text, std::string_view origin, const ParamSchema& schema,
                   const std::vector<ParamOverride>& overrides)
{
  if (overrides.empty()) {
    return parseParams(yaml_text, origin, schema);
  }
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml_text));
  } catch (const YAML::Exception&) {
    return parseParams(yaml_text, origin, schema);  // reports the syntax error
  }
  if (root.IsNull()) {
    root = YAML::Node(YAML::NodeType::Map);
  }
  if (!root.IsMap()) {
    return parseParams(yaml_text, origin, schema);
  }
  for (const auto& o : overrides) {
    YAML::Node value;
    try {
      value = YAML::Load(o.value);
    } catch (const YAML::Exception& e) {
      throw ConfigError({std::string(origin) + ":" + o.key + ": " + o.value + ": --set value is not YAML (" +
                         e.msg + ")"});
    }
    // Walk down the dotted key, creating maps on the way; a scalar in the way is replaced.
    std::vector<YAML::Node> chain{root};
    std::size_t start = 0;
    while (true) {
      const auto dot = o.key.find('.', start);
      const std::string part = o.key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
      if (part.empty()) {
        throw ConfigError({std::string(origin) + ":" + o.key + ": " + o.value + ": --set key has an empty part"});
      }
      YAML::Node parent = chain.back();
      if (dot == std::string::npos) {
        parent[part] = value;
        break;
      }
      if (!parent[part] || !parent[part].IsMap()) {
        parent[part] = YAML::Node(YAML::NodeType::Map);
      }
      chain.push_back(parent[part]);
      start = dot + 1;
    }
  }
  YAML::Emitter out;
  out << root;
  return parseParams(out.c_str(), origin, schema);
}

Params loadParams(const std::filesystem::path& file, const ParamSchema& schema)
{
  return parseParams(readTextFile(file), file.string(), schema);
}

std::string configProblem(std::string_view origin, std::string_view key, const ParamValue& value,
                          std::string_view why)
{
  return std::string(origin) + ":" + std::string(key) + ": " + formatValue(value) + ": " + std::string(why);
}

std::filesystem::path configPath(const Params& params, std::string_view key,
                                 const std::filesystem::path& defaults_dir)
{
  const std::filesystem::path path(params.getString(key));
  if (path.empty() || path.is_absolute()) {
    return path;
  }
  const bool from_file = !params.origin().starts_with("<");
  return (from_file ? std::filesystem::path(params.origin()).parent_path() : defaults_dir) / path;
}

Params defaultParams(const ParamSchema& schema) { return parseParams("", "<defaults>", schema); }

}  // namespace quad::common
