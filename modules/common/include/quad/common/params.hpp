// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Declared, validated module parameters.
///
/// Every parameter a module reads is declared once in a ParamSchema with its type, default,
/// range and unit (as PX4 declares its parameters in *_params.yaml). Loading a YAML file
/// against the schema rejects unknown keys, wrong types, values out of range and non-finite
/// numbers, each reported as `file:key: value: reason`, so a node refuses to start on a bad
/// config instead of flying with a silently clamped or defaulted value.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace quad::common {

/// A value a parameter can hold. Integers are int64; vectors are fixed-length lists of doubles.
using ParamValue = std::variant<bool, std::int64_t, double, std::string, std::vector<double>>;

enum class ParamType { kBool, kInt, kDouble, kString, kVector };

std::string_view toString(ParamType type);

/// Declaration of one parameter. Keys of nested YAML maps are joined with '.'.
struct ParamSpec {
  std::string key;
  ParamType type = ParamType::kDouble;
  /// Value when the file does not set the key; absent means the key is required.
  std::optional<ParamValue> default_value;
  /// Inclusive bounds for numbers (and every element of a vector).
  std::optional<double> min;
  std::optional<double> max;
  /// Required length of a vector parameter; 0 accepts any length >= 1.
  std::size_t size = 0;
  /// Allowed values of a string parameter; empty accepts any string.
  std::vector<std::string> choices;
  /// SI unit, for documentation and messages ("m", "rad/s", "" for none).
  std::string unit;
  std::string description;
};

/// Thrown on a bad config. what() holds one `file:key: value: reason` line per problem.
class ConfigError : public std::runtime_error {
public:
  explicit ConfigError(std::vector<std::string> problems);
  const std::vector<std::string>& problems() const { return problems_; }

private:
  std::vector<std::string> problems_;
};

/// The set of parameters of one module. Declarations are checked when they are added:
/// a default outside its own range or of the wrong type is a programming error (throws
/// std::logic_error).
class ParamSchema {
public:
  ParamSchema& add(ParamSpec spec);

  ParamSchema& addBool(std::string key, bool default_value, std::string description);
  ParamSchema& addInt(std::string key, std::optional<std::int64_t> default_value,
                      std::optional<double> min, std::optional<double> max, std::string unit,
                      std::string description);
  ParamSchema& addDouble(std::string key, std::optional<double> default_value,
                         std::optional<double> min, std::optional<double> max, std::string unit,
                         std::string description);
  ParamSchema& addString(std::string key, std::optional<std::string> default_value,
                         std::vector<std::string> choices, std::string description);
  ParamSchema& addVector(std::string key, std::optional<std::vector<double>> default_value,
                         std::size_t size, std::optional<double> min, std::optional<double> max,
                         std::string unit, std::string description);

  const ParamSpec* find(std::string_view key) const;
  const std::vector<ParamSpec>& specs() const { return specs_; }

private:
  std::vector<ParamSpec> specs_;
};

/// Validated parameter values: every declared key is present, with its declared type.
class Params {
public:
  Params() = default;
  Params(std::map<std::string, ParamValue, std::less<>> values, std::string origin);

  bool getBool(std::string_view key) const;
  std::int64_t getInt(std::string_view key) const;
  double getDouble(std::string_view key) const;
  const std::string& getString(std::string_view key) const;
  const std::vector<double>& getVector(std::string_view key) const;

  /// Where the values came from (a file path, or "<defaults>").
  const std::string& origin() const { return origin_; }

private:
  const ParamValue& at(std::string_view key) const;

  std::map<std::string, ParamValue, std::less<>> values_;
  std::string origin_;
};

/// Parses YAML text against the schema. `origin` names the source in error messages.
/// Throws ConfigError listing every problem found.
Params parseParams(std::string_view yaml_text, std::string_view origin, const ParamSchema& schema);

/// Reads and validates a YAML file. An unreadable file is a ConfigError too.
Params loadParams(const std::filesystem::path& file, const ParamSchema& schema);

/// One `key=value` given on a command line (`--set sim.mode=lockstep`): the value is YAML
/// text and replaces what the file says under the dotted key.
struct ParamOverride {
  std::string key;
  std::string value;
};

/// Parses "key=value"; throws ConfigError naming the text when there is no '=' or no key.
ParamOverride parseOverride(std::string_view text);

/// Like parseParams, with `overrides` applied on top of the YAML text before validation, so
/// an override is checked like the file's own values. Relative paths stay relative to the
/// file named by `origin`.
Params parseParams(std::string_view yaml_text, std::string_view origin, const ParamSchema& schema,
                   const std::vector<ParamOverride>& overrides);

/// The schema's defaults; throws ConfigError if a key has no default.
Params defaultParams(const ParamSchema& schema);

/// One problem line in quad's format, `origin:key: value: why`, for checks across keys that
/// a schema cannot express (a minimum above a maximum, ...).
std::string configProblem(std::string_view origin, std::string_view key, const ParamValue& value,
                          std::string_view why);

/// A file path a config names under `key`: absolute as written; relative to the folder of
/// the config file; for the schema's defaults (no file), relative to `defaults_dir`. Empty
/// stays empty (no file).
std::filesystem::path configPath(const Params& params, std::string_view key,
                                 const std::filesystem::path& defaults_dir);

/// Renders a value as it would be written in YAML ("0.5", "[1, 2, 3]", "true").
std::string formatValue(const ParamValue& value);

}  // namespace quad::common
