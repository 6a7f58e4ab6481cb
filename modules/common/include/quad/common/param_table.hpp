// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Parameters declared once: each entry of a ParamTable names its key, unit, bounds and
/// meaning and the field of a config struct that it fills. The table gives the schema that
/// validates a file (params.hpp) and reads the validated values into the struct, so no key is
/// spelled a second time to read it back. A parameter's default is its field's value in a
/// default-constructed struct: the struct's initialiser is the one place a default is written.
///
/// A field is named by a function from the struct to a reference to it, a lambda:
///
/// ```cpp
/// table.number("gains.position", [](Config& c) -> double& { return c.gains.kx; },
///              {0.01, 1e4}, "N/m", "k_x");
/// ```

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "quad/common/name_list.hpp"
#include "quad/common/params.hpp"
#include "quad/common/time.hpp"

namespace quad::common {

/// Inclusive bounds of a number, or of every element of a vector; either may be open.
struct Range {
  std::optional<double> min;
  std::optional<double> max;
};

/// kRequired: the file must set the key (the field's own value is no default).
enum class Need { kDefaulted, kRequired };

template <typename Config>
class ParamTable {
public:
  /// The type a field function `F` refers to.
  template <typename F>
  using FieldType = std::remove_reference_t<std::invoke_result_t<F, Config&>>;

  /// A floating-point or integral number (declared a double or an integer accordingly).
  template <typename F>
  ParamTable& number(std::string key, F field, Range range, std::string unit, std::string description,
                     Need need = Need::kDefaulted)
  {
    using T = FieldType<F>;
    static_assert(std::is_arithmetic_v<T> && !std::is_same_v<T, bool>, "number() takes a numeric field");
    ParamSpec spec{std::move(key), std::is_integral_v<T> ? ParamType::kInt : ParamType::kDouble, {},
                   range.min, range.max, 0, {}, std::move(unit), std::move(description)};
    if (need == Need::kDefaulted) {
      const T value = field(defaults_);
      if constexpr (std::is_integral_v<T>) {
        spec.default_value = static_cast<std::int64_t>(value);
      } else {
        spec.default_value = static_cast<double>(value);
      }
    }
    const std::string k = declare(std::move(spec));
    readers_.push_back([k, field](const Params& p, Config& c, const std::filesystem::path&) {
      if constexpr (std::is_integral_v<T>) {
        field(c) = static_cast<T>(p.getInt(k));
      } else {
        field(c) = static_cast<T>(p.getDouble(k));
      }
    });
    return *this;
  }

  /// A duration written in seconds, kept in integer nanoseconds.
  template <typename F>
  ParamTable& seconds(std::string key, F field_ns, Range range, std::string description)
  {
    static_assert(std::is_same_v<FieldType<F>, std::int64_t>, "seconds() fills a field of nanoseconds");
    ParamSpec spec{std::move(key), ParamType::kDouble, toSeconds(field_ns(defaults_)),
                   range.min, range.max, 0, {}, "s", std::move(description)};
    const std::string k = declare(std::move(spec));
    readers_.push_back([k, field_ns](const Params& p, Config& c, const std::filesystem::path&) {
      field_ns(c) = toNanoseconds(p.getDouble(k));
    });
    return *this;
  }

  /// A fixed-length list of numbers: a field with size() and operator[] (an Eigen vector,
  /// std::array); its length is the default's.
  template <typename F>
  ParamTable& vector(std::string key, F field, Range range, std::string unit, std::string description,
                     Need need = Need::kDefaulted)
  {
    using V = FieldType<F>;
    V& value = field(defaults_);
    const auto n = static_cast<std::size_t>(value.size());
    ParamSpec spec{std::move(key), ParamType::kVector, {}, range.min, range.max, n, {}, std::move(unit),
                   std::move(description)};
    if (need == Need::kDefaulted) {
      std::vector<double> list(n);
      for (std::size_t i = 0; i < n; ++i) {
        list[i] = static_cast<double>(value[static_cast<decltype(value.size())>(i)]);
      }
      spec.default_value = list;
    }
    const std::string k = declare(std::move(spec));
    readers_.push_back([k, field](const Params& p, Config& c, const std::filesystem::path&) {
      const std::vector<double>& list = p.getVector(k);
      V& out = field(c);
      for (std::size_t i = 0; i < list.size(); ++i) {
        out[static_cast<decltype(out.size())>(i)] = list[i];
      }
    });
    return *this;
  }

  template <typename F>
  ParamTable& flag(std::string key, F field, std::string description)
  {
    static_assert(std::is_same_v<FieldType<F>, bool>, "flag() fills a bool");
    ParamSpec spec{std::move(key), ParamType::kBool, field(defaults_), {}, {}, 0, {}, "", std::move(description)};
    const std::string k = declare(std::move(spec));
    readers_.push_back(
        [k, field](const Params& p, Config& c, const std::filesystem::path&) { field(c) = p.getBool(k); });
    return *this;
  }

  /// Free text, or one of `choices` when they are given.
  template <typename F>
  ParamTable& text(std::string key, F field, std::vector<std::string> choices, std::string description)
  {
    static_assert(std::is_same_v<FieldType<F>, std::string>, "text() fills a std::string");
    ParamSpec spec{std::move(key), ParamType::kString, field(defaults_), {}, {}, 0, std::move(choices), "",
                   std::move(description)};
    const std::string k = declare(std::move(spec));
    readers_.push_back(
        [k, field](const Params& p, Config& c, const std::filesystem::path&) { field(c) = p.getString(k); });
    return *this;
  }

  /// One of named values of an enumeration (or any comparable type): the file writes the name.
  template <typename F, typename E = FieldType<F>>
  ParamTable& choice(std::string key, F field, std::vector<std::pair<std::string, E>> names, std::string description)
  {
    std::vector<std::string> choices;
    std::optional<ParamValue> default_name;
    for (const auto& [name, value] : names) {
      choices.push_back(name);
      if (value == field(defaults_)) {
        default_name = name;
      }
    }
    if (!default_name) {
      throw std::logic_error("parameter " + key + ": its field's default has no name");
    }
    ParamSpec spec{std::move(key), ParamType::kString, *default_name, {}, {}, 0, std::move(choices), "",
                   std::move(description)};
    const std::string k = declare(std::move(spec));
    readers_.push_back([k, field, names](const Params& p, Config& c, const std::filesystem::path&) {
      for (const auto& [name, value] : names) {
        if (name == p.getString(k)) {
          field(c) = value;
        }
      }
    });
    return *this;
  }

  /// A file: absolute as written, else relative to the config file's folder (to the
  /// defaults folder for the schema's defaults; configPath). Empty stays empty.
  template <typename F>
  ParamTable& path(std::string key, F field, std::string description)
  {
    static_assert(std::is_same_v<FieldType<F>, std::filesystem::path>, "path() fills a std::filesystem::path");
    ParamSpec spec{std::move(key), ParamType::kString, field(defaults_).string(), {}, {}, 0, {}, "",
                   std::move(description)};
    const std::string k = declare(std::move(spec));
    readers_.push_back([k, field](const Params& p, Config& c, const std::filesystem::path& defaults_dir) {
      field(c) = configPath(p, k, defaults_dir);
    });
    return *this;
  }

  /// A comma-separated list of names ("plant, control"), blanks around each dropped; into a
  /// std::vector<std::string> or std::set<std::string>.
  template <typename F>
  ParamTable& list(std::string key, F field, std::string description)
  {
    using List = FieldType<F>;
    std::string joined;
    for (const auto& item : field(defaults_)) {
      joined += (joined.empty() ? "" : ",") + item;
    }
    ParamSpec spec{std::move(key), ParamType::kString, joined, {}, {}, 0, {}, "", std::move(description)};
    const std::string k = declare(std::move(spec));
    readers_.push_back([k, field](const Params& p, Config& c, const std::filesystem::path&) {
      List& out = field(c);
      out = {};
      for (auto& item : nameList(p.getString(k))) {
        out.insert(out.end(), std::move(item));
      }
    });
    return *this;
  }

  /// Another table's parameters, for a part of this struct (`part`), under the same keys.
  template <typename F, typename Part = FieldType<F>>
  ParamTable& include(const ParamTable<Part>& other, F part)
  {
    for (const ParamSpec& spec : other.schema().specs()) {
      declare(spec);
    }
    for (const auto& reader : other.readers_) {
      readers_.push_back([reader, part](const Params& p, Config& c, const std::filesystem::path& defaults_dir) {
        reader(p, part(c), defaults_dir);
      });
    }
    return *this;
  }

  const ParamSchema& schema() const { return schema_; }

  /// The struct the validated `params` describe. `defaults_dir`: what relative paths resolve
  /// against when the values are the schema's defaults (no file).
  Config read(const Params& params, const std::filesystem::path& defaults_dir = {}) const
  {
    Config c;
    readInto(params, c, defaults_dir);
    return c;
  }

  void readInto(const Params& params, Config& c, const std::filesystem::path& defaults_dir = {}) const
  {
    for (const auto& reader : readers_) {
      reader(params, c, defaults_dir);
    }
  }

private:
  template <typename>
  friend class ParamTable;

  /// Adds the declaration (checked by the schema) and returns its key.
  std::string declare(ParamSpec spec)
  {
    schema_.add(std::move(spec));
    return schema_.specs().back().key;
  }

  Config defaults_{};
  ParamSchema schema_;
  std::vector<std::function<void(const Params&, Config&, const std::filesystem::path&)>> readers_;
};

}  // namespace quad::common
