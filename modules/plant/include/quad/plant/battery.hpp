// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The flight battery: a lithium-polymer pack of cells in series, drawn on by the rotors and
/// the avionics. Its open-circuit voltage follows a cell's discharge curve over the charge
/// left; under load the terminal voltage sags by the current through the pack's internal
/// resistance (the classic Thevenin model without its RC branch, which a 1 ms step would not
/// resolve usefully). The rotors' speed controllers reach their rated top speed only down to
/// a rated cell voltage: below it the top speed falls in proportion to the voltage, and with
/// it (as its square) the most thrust a rotor can give. A cell that fails short takes its
/// voltage away and the pack goes on with the others.
///
/// Time enters as an argument; the core never reads a clock.

#include "quad/plant/dynamics.hpp"

namespace quad::plant {

struct BatteryConfig {
  bool enabled = true;                  ///< false: an ideal supply (no drain, no sag)
  int cells = 4;                        ///< in series (4S)
  double capacity = 5.0;                ///< [Ah]
  double initial_charge = 1.0;          ///< fraction of the capacity at the start
  double resistance = 0.02;             ///< [Ω] the pack's internal resistance
  double rated_cell_voltage = 3.7;      ///< [V] a cell's voltage at which the rotors still reach their top speed
  double motor_efficiency = 0.75;       ///< shaft power over electric power, motors and speed controllers
  double avionics_power = 5.0;          ///< [W] flight computer, sensors, radios
};

/// [V] a lithium-polymer cell at rest with `charge` (fraction, clamped to 0 … 1) left:
/// 4.20 V full, 3.80 V at half, 3.62 V at a tenth, falling steeply below it to 3.00 V empty.
double cellOpenCircuitVoltage(double charge);

class Battery {
public:
  /// Throws std::invalid_argument on a config out of its ranges (no cells, no capacity, a
  /// charge outside 0 … 1, a negative resistance or power, an efficiency outside (0, 1]).
  explicit Battery(BatteryConfig config);

  /// Draws `power` [W] (>= 0) for `dt` [s]. The current solves power = (OCV − I R) I, the
  /// lower root; when the pack cannot give that much power it gives the most it can, at
  /// I = OCV / 2R (the voltage has halved). Nothing is drawn once the pack is empty.
  void draw(double power, double dt);

  /// [W] the pack's power for rotors spinning at `rotor_speed` (shaft power k_m ω³ each,
  /// scaled by the fraction `efficiency` of its thrust and torque a rotor has left) plus the
  /// avionics.
  double powerFor(const RotorArray& rotor_speed, const RotorArray& efficiency, double torque_coefficient) const;

  /// `count` more cells fail short (at most all of them).
  void loseCells(int count);

  const BatteryConfig& config() const { return config_; }
  int workingCells() const { return config_.cells - lost_cells_; }
  double charge() const { return charge_ah_ / config_.capacity; }  ///< fraction left
  double chargeAh() const { return charge_ah_; }                  ///< [Ah] left
  double openCircuitVoltage() const;                              ///< [V]
  double voltage() const { return voltage_; }                     ///< [V] at the terminals, under the last load
  double current() const { return current_; }                     ///< [A] of the last draw
  double energyDrawn() const { return energy_drawn_; }            ///< [J] since the start
  bool empty() const { return charge_ah_ <= 0.0 || workingCells() == 0; }
  /// The fraction of the rotors' rated top speed the voltage allows now: 1 down to the
  /// rated voltage (of the cells the pack was built with), then the voltage over it; 0 empty.
  double supply() const;

private:
  BatteryConfig config_;
  double charge_ah_;
  int lost_cells_ = 0;
  double voltage_;
  double current_ = 0.0;
  double energy_drawn_ = 0.0;
};

}  // namespace quad::plant
