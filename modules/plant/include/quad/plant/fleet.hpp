// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Several vehicles in one world, on one clock: each a Simulation of its own (its dynamics,
/// sensors, battery, faults and generators), stepped together. Each vehicle's depth camera
/// sees the others (as their bounding spheres, where they were when the step began), and two
/// vehicles whose spheres meet collide: a collision event for each of them, once per contact,
/// as with an obstacle. Vehicles do not push each other: a contact is counted, not resolved.

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "quad/plant/simulation.hpp"

namespace quad::plant {

/// One vehicle of a fleet.
struct FleetVehicle {
  std::uint32_t id = 0;  ///< its vehicle id (topics' key); unique in the fleet
  vehicle::VehicleParams params;
  Vector3 start = Vector3::Zero();  ///< [m] where it starts, level and at rest
  Vector3 goal = Vector3::Zero();   ///< [m] its goal (the world it sees has its start and goal)
  std::vector<Fault> schedule;      ///< faults injected into it alone
};

class Fleet {
public:
  /// Vehicle i flies `world`'s obstacles and bounds from its own start; its generators are
  /// seeded with config.seed + i, so that a fleet of one flies as a lone Simulation of that
  /// seed. Throws std::invalid_argument, naming the vehicles, when there are none, an id
  /// repeats, or two start with their spheres in contact.
  Fleet(std::vector<FleetVehicle> vehicles, const world::World& world, const SimulationConfig& config);

  /// What the constructor would refuse `vehicles` for, naming the vehicles; nothing when they
  /// make a fleet.
  static std::optional<std::string> problem(const std::vector<FleetVehicle>& vehicles);

  std::size_t size() const { return vehicles_.size(); }
  std::uint32_t id(std::size_t i) const { return ids_.at(i); }
  /// Every vehicle's id, in the fleet's order.
  const std::vector<std::uint32_t>& ids() const { return ids_; }
  /// The index of the vehicle with this id, if it is in the fleet.
  std::optional<std::size_t> indexOf(std::uint32_t id) const;
  Simulation& vehicle(std::size_t i) { return vehicles_.at(i); }
  const Simulation& vehicle(std::size_t i) const { return vehicles_.at(i); }
  std::int64_t timeNs() const { return vehicles_.front().timeNs(); }

  /// Steps every vehicle once; element i holds vehicle i's outputs, its collisions with other
  /// vehicles among its events.
  std::vector<StepOutputs> step();

  /// Vehicle i's collisions so far: with obstacles, the bounds and other vehicles.
  std::uint64_t collisionCount(std::size_t i) const;
  /// [m] The least distance between two vehicles' spheres after any step so far (negative
  /// while they overlapped); infinite for a fleet of one.
  double minimumSeparation() const { return min_separation_; }

private:
  std::vector<Simulation> vehicles_;
  std::vector<std::uint32_t> ids_;
  std::vector<std::uint64_t> vehicle_collisions_;  // per vehicle: with other vehicles
  std::set<std::pair<std::size_t, std::size_t>> touching_;  // pairs (i < j) in contact now
  double min_separation_;
  std::vector<world::Sphere> others_scratch_;  // the others of the vehicle being set up
};

}  // namespace quad::plant
