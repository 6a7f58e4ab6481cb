// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant/battery.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace quad::plant {

namespace {

/// A lithium-polymer cell's open-circuit voltage [V] at rest, by the fraction of charge left
/// (a typical discharge curve at low rate: a plateau from 3.7 to 3.9 V, steep at both ends).
constexpr std::array<std::pair<double, double>, 12> kCellCurve{{{0.00, 3.00},
                                                                {0.05, 3.45},
                                                                {0.10, 3.62},
                                                                {0.20, 3.70},
                                                                {0.30, 3.74},
                                                                {0.40, 3.77},
                                                                {0.50, 3.80},
                                                                {0.60, 3.84},
                                                                {0.70, 3.90},
                                                                {0.80, 3.97},
                                                                {0.90, 4.06},
                                                                {1.00, 4.20}}};

void require(bool ok, const std::string& what)
{
  if (!ok) {
    throw std::invalid_argument("battery: " + what);
  }
}

}  // namespace

double cellOpenCircuitVoltage(double charge)
{
  const double c = std::clamp(charge, 0.0, 1.0);
  for (std::size_t i = 1; i < kCellCurve.size(); ++i) {
    const auto& [c1, v1] = kCellCurve[i];
    if (c <= c1) {
      const auto& [c0, v0] = kCellCurve[i - 1];
      return v0 + (v1 - v0) * (c - c0) / (c1 - c0);
    }
  }
  return kCellCurve.back().second;
}

Battery::Battery(BatteryConfig config) : config_(config)
{
  require(config_.cells >= 1, "cells must be at least 1, not " + std::to_string(config_.cells));
  require(config_.capacity > 0.0 && std::isfinite(config_.capacity), "capacity must be above 0 Ah");
  require(config_.initial_charge >= 0.0 && config_.initial_charge <= 1.0, "initial charge must lie in 0 ... 1");
  require(config_.resistance >= 0.0 && std::isfinite(config_.resistance), "resistance must be finite and >= 0");
  require(config_.rated_cell_voltage > 0.0 && std::isfinite(config_.rated_cell_voltage),
          "rated cell voltage must be above 0 V");
  require(config_.motor_efficiency > 0.0 && config_.motor_efficiency <= 1.0, "motor efficiency must lie in (0, 1]");
  require(config_.avionics_power >= 0.0 && std::isfinite(config_.avionics_power), "avionics power must be >= 0 W");
  charge_ah_ = config_.initial_charge * config_.capacity;
  voltage_ = openCircuitVoltage();
}

double Battery::openCircuitVoltage() const
{
  return charge_ah_ <= 0.0 ? 0.0 : workingCells() * cellOpenCircuitVoltage(charge());
}

double Battery::powerFor(const RotorArray& rotor_speed, const RotorArray& efficiency, double torque_coefficient) const
{
  double shaft = 0.0;
  for (std::size_t i = 0; i < rotor_speed.size(); ++i) {
    const double w = rotor_speed[i];
    shaft += efficiency[i] * torque_coefficient * w * w * w;
  }
  return shaft / config_.motor_efficiency + config_.avionics_power;
}

void Battery::draw(double power, double dt)
{
  const double ocv = openCircuitVoltage();
  const double p = std::max(0.0, power);
  const double r = config_.resistance;
  if (ocv <= 0.0) {
    current_ = 0.0;
  } else if (r == 0.0) {
    current_ = p / ocv;
  } else {
    // (OCV − I R) I = P: the lower root is the operating point; past the top of the
    // parabola (P > OCV² / 4R) the pack gives its most, at half its voltage.
    const double discriminant = ocv * ocv - 4.0 * r * p;
    current_ = discriminant >= 0.0 ? (ocv - std::sqrt(discriminant)) / (2.0 * r) : ocv / (2.0 * r);
  }
  voltage_ = ocv - current_ * r;
  energy_drawn_ += voltage_ * current_ * dt;
  charge_ah_ = std::max(0.0, charge_ah_ - current_ * dt / 3600.0);
}

void Battery::loseCells(int count)
{
  lost_cells_ = std::clamp(lost_cells_ + std::max(0, count), 0, config_.cells);
  voltage_ = std::max(0.0, openCircuitVoltage() - current_ * config_.resistance);
}

double Battery::supply() const
{
  if (empty()) {
    return 0.0;
  }
  return std::clamp(voltage_ / (config_.cells * config_.rated_cell_voltage), 0.0, 1.0);
}

}  // namespace quad::plant
