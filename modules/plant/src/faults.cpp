// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant/faults.hpp"

#include <yaml-cpp/yaml.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "quad/common/params.hpp"
#include "quad/common/yaml_input.hpp"
#include "quad/common/time.hpp"

namespace quad::plant {

std::string_view toString(Sensor s)
{
  switch (s) {
    case Sensor::kDepth:
      return "depth";
    case Sensor::kImu:
      return "imu";
    case Sensor::kState:
      return "state";
    case Sensor::kPosition:
      return "position";
    case Sensor::kBaro:
      return "baro";
    case Sensor::kMag:
      return "mag";
    case Sensor::kRange:
      return "range";
    case Sensor::kRangeUp:
      return "range_up";
  }
  return "?";
}

namespace {
constexpr std::array kSensors{Sensor::kDepth, Sensor::kImu, Sensor::kState, Sensor::kPosition, Sensor::kBaro, Sensor::kMag,
                              Sensor::kRange, Sensor::kRangeUp};
}  // namespace

std::string sensorNames()
{
  std::string out;
  for (std::size_t i = 0; i < kSensors.size(); ++i) {
    out += (i == 0 ? "" : i + 1 == kSensors.size() ? " or " : ", ") + std::string(toString(kSensors[i]));
  }
  return out;
}

std::optional<Sensor> parseSensor(std::string_view text)
{
  for (const Sensor s : kSensors) {
    if (toString(s) == text) {
      return s;
    }
  }
  return std::nullopt;
}

std::string_view toString(Fault::Kind k)
{
  switch (k) {
    case Fault::Kind::kMotor:
      return "motor";
    case Fault::Kind::kSensorDropout:
      return "sensor_dropout";
    case Fault::Kind::kSensorStuck:
      return "sensor_stuck";
    case Fault::Kind::kSensorNoise:
      return "sensor_noise";
    case Fault::Kind::kSensorOffset:
      return "sensor_offset";
    case Fault::Kind::kWindGust:
      return "wind_gust";
    case Fault::Kind::kPush:
      return "push";
    case Fault::Kind::kCellLoss:
      return "cell_loss";
  }
  return "?";
}

std::string Fault::describe() const
{
  std::string out = "fault " + std::to_string(id) + " " + std::string(toString(kind));
  switch (kind) {
    case Kind::kMotor:
      out += ": rotor " + std::to_string(rotor) + " at " + common::formatValue(magnitude) + " efficiency";
      break;
    case Kind::kSensorDropout:
    case Kind::kSensorStuck:
      out += ": " + std::string(toString(sensor));
      break;
    case Kind::kSensorNoise:
      out += ": " + std::string(toString(sensor)) + " +" + common::formatValue(magnitude) + " std dev";
      break;
    case Kind::kSensorOffset:
      out += ": " + std::string(toString(sensor)) + " offset " +
             common::formatValue(std::vector<double>{offset.x(), offset.y(), offset.z()});
      break;
    case Kind::kWindGust:
      out += ": wind " + common::formatValue(std::vector<double>{wind_W.x(), wind_W.y(), wind_W.z()}) + " m/s";
      break;
    case Kind::kPush:
      out += ": force " + common::formatValue(std::vector<double>{force_W.x(), force_W.y(), force_W.z()}) + " N";
      break;
    case Kind::kCellLoss:
      out += ": " + std::to_string(cells) + (cells == 1 ? " battery cell" : " battery cells") + " failed short";
      break;
  }
  return out;
}

std::optional<Fault> parseFault(common::YamlReader& r, YAML::Node f, const std::string& key,
                                const std::set<std::string>& extra_keys)
{
  if (!f.IsMap()) {
    r.problem(key, f, "expected a map");
    return std::nullopt;
  }
  const auto number = [&](const char* name, std::optional<double> fallback, double lo, double hi) {
    return r.number(f[name], key + "." + name, fallback, lo, hi);
  };
  Fault fault;
  const std::string kind = f["kind"].IsScalar() ? f["kind"].Scalar() : "";
  std::set<std::string> allowed = extra_keys;
  allowed.insert({"kind", "duration"});
  const auto duration = number("duration", 0.0, 0.0, 1e7);
  bool ok = duration.has_value();
  if (kind == "motor") {
    allowed.insert({"rotor", "efficiency"});
    fault.kind = Fault::Kind::kMotor;
    const auto rotor = number("rotor", std::nullopt, 0.0, 3.0);
    const auto eff = number("efficiency", std::nullopt, 0.0, 1.0);
    ok = ok && rotor && eff;
    if (rotor && eff) {
      fault.rotor = static_cast<int>(*rotor);
      fault.magnitude = *eff;
    }
  } else if (kind == "sensor_dropout" || kind == "sensor_stuck" || kind == "sensor_noise" || kind == "sensor_offset") {
    allowed.insert("sensor");
    fault.kind = kind == "sensor_dropout" ? Fault::Kind::kSensorDropout
                 : kind == "sensor_stuck" ? Fault::Kind::kSensorStuck
                 : kind == "sensor_noise" ? Fault::Kind::kSensorNoise
                                          : Fault::Kind::kSensorOffset;
    const auto sensor = f["sensor"].IsScalar() ? parseSensor(f["sensor"].Scalar()) : std::nullopt;
    if (!sensor) {
      r.problem(key + ".sensor", f["sensor"], "expected " + sensorNames());
      ok = false;
    } else {
      fault.sensor = *sensor;
    }
    if (kind == "sensor_noise") {
      allowed.insert("std_dev");
      const auto s = number("std_dev", std::nullopt, 0.0, 1e3);
      ok = ok && s;
      fault.magnitude = s.value_or(0.0);
    }
    if (kind == "sensor_offset") {
      allowed.insert("offset");
      const auto v = r.numbers(f["offset"], key + ".offset", 3, -1e4, 1e4);
      ok = ok && v;
      if (v) {
        fault.offset = {(*v)[0], (*v)[1], (*v)[2]};
      }
    }
  } else if (kind == "wind_gust" || kind == "push") {
    // A vector in the world frame: the gust's wind [m/s], the push's force [N].
    const bool gust = kind == "wind_gust";
    const std::string name = gust ? "wind" : "force";
    allowed.insert(name);
    fault.kind = gust ? Fault::Kind::kWindGust : Fault::Kind::kPush;
    const auto v = r.numbers(f[name], key + "." + name, 3, -1e3, 1e3);
    ok = ok && v;
    if (v) {
      (gust ? fault.wind_W : fault.force_W) = {(*v)[0], (*v)[1], (*v)[2]};
    }
  } else if (kind == "cell_loss") {
    allowed.insert("cells");
    fault.kind = Fault::Kind::kCellLoss;
    const auto cells = number("cells", 1.0, 1.0, 16.0);
    ok = ok && cells;
    fault.cells = static_cast<int>(cells.value_or(1.0));
  } else {
    r.problem(key + ".kind", f["kind"],
              "expected motor, sensor_dropout, sensor_stuck, sensor_noise, sensor_offset, wind_gust, push or cell_loss");
    return std::nullopt;
  }
  for (const auto& entry : f) {
    if (!allowed.contains(entry.first.Scalar())) {
      r.problem(key + "." + entry.first.Scalar(), entry.second, "unknown key for kind " + kind);
      ok = false;
    }
  }
  if (!ok) {
    return std::nullopt;
  }
  fault.duration_ns = common::toNanoseconds(*duration);
  return fault;
}

std::vector<Fault> parseFaultSchedule(std::string_view yaml_text, std::string_view origin)
{
  common::YamlReader r(origin);
  YAML::Node root = common::parseYaml(yaml_text, origin);  // not const: a missing key must read as undefined, not invalid
  std::vector<Fault> out;
  if (root.IsNull()) {
    return out;
  }
  if (!root.IsSequence()) {
    r.problem("(top level)", root, "expected a list of faults");
    r.throwIfAny();
  }
  std::set<std::uint32_t> ids;
  for (std::size_t i = 0; i < root.size(); ++i) {
    YAML::Node f = root[i];
    const std::string key = "[" + std::to_string(i) + "]";
    auto fault = parseFault(r, f, key, {"id", "at"});
    if (!f.IsMap()) {
      continue;
    }
    const auto id = r.number(f["id"], key + ".id", std::nullopt, 1.0, 4294967295.0);
    const auto at = r.number(f["at"], key + ".at", std::nullopt, 0.0, 1e7);
    if (!fault || !id || !at) {
      continue;
    }
    fault->id = static_cast<std::uint32_t>(*id);
    if (!ids.insert(fault->id).second) {
      r.problem(key + ".id", f["id"], "used twice");
      continue;
    }
    fault->start_ns = common::toNanoseconds(*at);
    out.push_back(*fault);
  }
  r.throwIfAny();
  return out;
}

std::vector<Fault> loadFaultSchedule(const std::filesystem::path& file)
{
  return parseFaultSchedule(common::readTextFile(file), file.string());
}

}  // namespace quad::plant
