// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant/fleet_file.hpp"

#include <cmath>
#include <map>
#include <optional>
#include <string>

#include "quad/common/payload_header.hpp"
#include "quad/common/yaml_input.hpp"
#include "quad/plant/faults.hpp"

namespace quad::plant {

namespace {

/// [m] A point within the world's bounds, or nothing (and a problem) when it is not one.
std::optional<Vector3> pointIn(common::YamlReader& r, const YAML::Node& node, const std::string& key,
                               const world::World& world)
{
  const auto v = r.numbers(node, key, 3, -1e6, 1e6);
  if (!v) {
    return std::nullopt;
  }
  const Vector3 p((*v)[0], (*v)[1], (*v)[2]);
  if (!world.bounds().contains(p)) {
    r.problem(key, node, "outside the world's bounds");
    return std::nullopt;
  }
  return p;
}

}  // namespace

std::vector<FleetVehicle> parseFleet(std::string_view yaml_text, std::string_view origin,
                                     const std::filesystem::path& folder, const world::World& world,
                                     const std::filesystem::path& default_vehicle)
{
  common::YamlReader r(origin);
  YAML::Node root = common::parseYaml(yaml_text, origin);  // not const: a missing key must read as undefined
  if (!root.IsMap()) {
    r.problem("(top level)", root, "expected a map with a list of vehicles");
    r.throwIfAny();
  }
  r.onlyKeys(root, "", {"vehicles"});
  YAML::Node listed = root["vehicles"];
  if (!listed.IsSequence() || listed.size() == 0) {
    r.problem("vehicles", listed, "expected a list of at least one vehicle");
    r.throwIfAny();
  }
  if (listed.size() > static_cast<std::size_t>(common::kMaxFleetVehicles)) {
    r.problem("vehicles", YAML::Node(std::to_string(listed.size()) + " vehicles"),
              "at most " + std::to_string(common::kMaxFleetVehicles) + " fly in one domain");
    r.throwIfAny();
  }
  const auto resolve = [&](const std::string& path) {
    const std::filesystem::path p(path);
    return p.is_absolute() ? p : folder / p;
  };
  std::vector<FleetVehicle> fleet;
  std::map<std::uint32_t, std::string> keys_of_ids;
  for (std::size_t i = 0; i < listed.size(); ++i) {
    const std::string key = "vehicles[" + std::to_string(i) + "]";
    YAML::Node item = listed[i];
    if (!item.IsMap()) {
      r.problem(key, item, "expected a map with id and start");
      continue;
    }
    r.onlyKeys(item, key + ".", {"id", "start", "goal", "vehicle", "faults"});
    const auto id = r.number(item["id"], key + ".id", std::nullopt, 0.0, common::kMaxVehicleId);
    if (id && *id != std::floor(*id)) {
      r.problem(key + ".id", item["id"], "expected a whole number");
    }
    const auto start = pointIn(r, item["start"], key + ".start", world);
    const auto goal = item["goal"].IsDefined() ? pointIn(r, item["goal"], key + ".goal", world)
                                               : std::optional<Vector3>(world.goal());
    const auto vehicle = r.text(item["vehicle"], key + ".vehicle", std::string());
    const auto faults = r.text(item["faults"], key + ".faults", std::string());
    if (!id || *id != std::floor(*id) || !start || !goal || !vehicle || !faults) {
      continue;
    }
    const auto vehicle_id = static_cast<std::uint32_t>(*id);
    if (const auto [it, fresh] = keys_of_ids.emplace(vehicle_id, key); !fresh) {
      r.problem(key + ".id", item["id"], "already the id of " + it->second);
      continue;
    }
    FleetVehicle v;
    v.id = vehicle_id;
    v.start = *start;
    v.goal = *goal;
    v.params = vehicle::loadVehicle(vehicle->empty() ? default_vehicle : resolve(*vehicle));
    if (!faults->empty()) {
      v.schedule = loadFaultSchedule(resolve(*faults));
    }
    fleet.push_back(std::move(v));
  }
  r.throwIfAny();
  return fleet;
}

std::vector<FleetVehicle> loadFleet(const std::filesystem::path& file, const world::World& world,
                                    const std::filesystem::path& default_vehicle)
{
  return parseFleet(common::readTextFile(file), file.string(), file.parent_path(), world, default_vehicle);
}

}  // namespace quad::plant
