// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant/fleet.hpp"

#include <limits>
#include <stdexcept>

#include <fmt/format.h>

namespace quad::plant {

namespace {

double radiusOf(const Simulation& sim) { return sim.dynamics().params().radius; }

}  // namespace

std::optional<std::string> Fleet::problem(const std::vector<FleetVehicle>& vehicles)
{
  if (vehicles.empty()) {
    return "a fleet needs at least one vehicle";
  }
  for (std::size_t i = 0; i < vehicles.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      const FleetVehicle& a = vehicles[j];
      const FleetVehicle& b = vehicles[i];
      if (a.id == b.id) {
        return fmt::format("vehicle id {} appears twice in the fleet", a.id);
      }
      const double apart = (a.start - b.start).norm();
      if (apart < a.params.radius + b.params.radius) {
        return fmt::format("vehicles {} and {} start {:.3f} m apart, in contact (radii {:.3f} + {:.3f} m)", a.id, b.id,
                           apart, a.params.radius, b.params.radius);
      }
    }
  }
  return std::nullopt;
}

Fleet::Fleet(std::vector<FleetVehicle> vehicles, const world::World& world, const SimulationConfig& config)
    : min_separation_(std::numeric_limits<double>::infinity())
{
  if (const auto why = problem(vehicles)) {
    throw std::invalid_argument(*why);
  }
  vehicles_.reserve(vehicles.size());
  for (FleetVehicle& v : vehicles) {
    SimulationConfig own = config;
    own.seed = config.seed + vehicles_.size();
    vehicles_.emplace_back(std::move(v.params), world.withStartAndGoal(v.start, v.goal), own, std::move(v.schedule));
    ids_.push_back(v.id);
  }
  vehicle_collisions_.assign(vehicles_.size(), 0);
}

std::optional<std::size_t> Fleet::indexOf(std::uint32_t id) const
{
  for (std::size_t i = 0; i < ids_.size(); ++i) {
    if (ids_[i] == id) {
      return i;
    }
  }
  return std::nullopt;
}

std::vector<StepOutputs> Fleet::step()
{
  const std::size_t n = vehicles_.size();
  if (n > 1) {
    // Every camera sees the others where they are as this step begins, whatever the order
    // the vehicles are stepped in.
    // The scratch vector is reused: a step allocates nothing for it.
    for (std::size_t i = 0; i < n; ++i) {
      others_scratch_.clear();
      for (std::size_t j = 0; j < n; ++j) {
        if (j != i) {
          others_scratch_.push_back({vehicles_[j].state().p_W, radiusOf(vehicles_[j])});
        }
      }
      vehicles_[i].setOthers(others_scratch_);
    }
  }
  std::vector<StepOutputs> out;
  out.reserve(n);
  for (Simulation& sim : vehicles_) {
    out.push_back(sim.step());
  }
  // Contacts between vehicles, where all of them are after the step: a collision is the start
  // of one, for each of the two.
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const Simulation& a = vehicles_[i];
      const Simulation& b = vehicles_[j];
      const double separation = (a.state().p_W - b.state().p_W).norm() - radiusOf(a) - radiusOf(b);
      min_separation_ = std::min(min_separation_, separation);
      const auto pair = std::make_pair(i, j);
      if (separation >= 0.0) {
        touching_.erase(pair);
        continue;
      }
      if (!touching_.insert(pair).second) {
        continue;  // still the same contact
      }
      for (const auto& [self, other] : {std::make_pair(i, j), std::make_pair(j, i)}) {
        ++vehicle_collisions_[self];
        SimEventRecord e{SimEventRecord::Kind::kCollision, vehicles_[self].timeNs(), vehicles_[self].state().p_W, -1,
                         fmt::format("hit vehicle {}", ids_[other])};
        e.other_vehicle = ids_[other];
        out[self].events.push_back(std::move(e));
      }
    }
  }
  return out;
}

std::uint64_t Fleet::collisionCount(std::size_t i) const
{
  return vehicles_.at(i).collisionCount() + vehicle_collisions_.at(i);
}

}  // namespace quad::plant
