// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/geofence.hpp"

#include <algorithm>

namespace quad::common {
namespace {

constexpr const char* kMinKey = "geofence.min";
constexpr const char* kMaxKey = "geofence.max";

/// The first axis whose minimum is not below its maximum, as words; nothing when none.
std::optional<std::string> inverted(const Geofence& fence, const std::string& max_key)
{
  for (std::size_t i = 0; i < 3; ++i) {
    if (!(fence.min[i] < fence.max[i])) {
      return "not below " + max_key + " on the " + "xyz"[i] + " axis";
    }
  }
  return std::nullopt;
}

}  // namespace

bool Geofence::bounded() const
{
  for (std::size_t i = 0; i < 3; ++i) {
    if (min[i] > -kUnbounded || max[i] < kUnbounded) {
      return true;
    }
  }
  return false;
}

const ParamTable<Geofence>& geofenceTable()
{
  static const ParamTable<Geofence> table = [] {
    ParamTable<Geofence> t;
    t.vector(kMinKey, [](Geofence& f) -> std::array<double, 3>& { return f.min; },
             {-Geofence::kUnbounded, Geofence::kUnbounded}, "m",
             "keep-in volume, lowest corner (world frame); the default leaves it unbounded")
        .vector(kMaxKey, [](Geofence& f) -> std::array<double, 3>& { return f.max; },
                {-Geofence::kUnbounded, Geofence::kUnbounded}, "m", "keep-in volume, highest corner (world frame)");
    return t;
  }();
  return table;
}

void checkGeofence(const Geofence& fence, std::string_view origin)
{
  if (const auto why = inverted(fence, kMaxKey)) {
    throw ConfigError({configProblem(origin, kMinKey, std::vector<double>(fence.min.begin(), fence.min.end()), *why)});
  }
}

std::optional<Geofence> readGeofence(const YAML::Node& node, const std::string& key, YamlReader& r)
{
  if (!node) {
    return std::nullopt;
  }
  r.onlyKeys(node, key + ".", {"min", "max"});
  const auto lo = r.numbers(node["min"], key + ".min", 3, -Geofence::kUnbounded, Geofence::kUnbounded);
  const auto hi = r.numbers(node["max"], key + ".max", 3, -Geofence::kUnbounded, Geofence::kUnbounded);
  if (!lo || !hi) {
    return std::nullopt;
  }
  Geofence fence;
  std::copy(lo->begin(), lo->end(), fence.min.begin());
  std::copy(hi->begin(), hi->end(), fence.max.begin());
  if (const auto why = inverted(fence, key + ".max")) {
    r.problem(key + ".min", node["min"], *why);
    return std::nullopt;
  }
  return fence;
}

std::vector<std::pair<std::string, std::string>> geofenceSets(const Geofence& fence)
{
  const auto text = [](const std::array<double, 3>& v) { return formatValue(std::vector<double>(v.begin(), v.end())); };
  return {{kMinKey, text(fence.min)}, {kMaxKey, text(fence.max)}};
}

}  // namespace quad::common
