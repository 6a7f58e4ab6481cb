// SPDX-License-Identifier: BSD-3-Clause
// The battery against closed-form cases: the discharge curve, the operating point of a
// resistive source, charge as the integral of current, a cell failing short, and in the
// simulation the energy the rotors draw and the top speed a sagging pack allows.
#include "quad/plant/battery.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "quad/plant/simulation.hpp"

namespace quad::plant {
namespace {

TEST(Battery, CellCurveRunsFromEmptyToFullAndRisesWithCharge)
{
  EXPECT_DOUBLE_EQ(cellOpenCircuitVoltage(0.0), 3.0);
  EXPECT_DOUBLE_EQ(cellOpenCircuitVoltage(1.0), 4.2);
  EXPECT_DOUBLE_EQ(cellOpenCircuitVoltage(-0.5), 3.0);  // clamped
  EXPECT_DOUBLE_EQ(cellOpenCircuitVoltage(1.5), 4.2);
  double before = cellOpenCircuitVoltage(0.0);
  for (int i = 1; i <= 1000; ++i) {
    const double v = cellOpenCircuitVoltage(i / 1000.0);
    EXPECT_GT(v, before) << "charge " << i / 1000.0;
    before = v;
  }
}

TEST(Battery, TheCurrentSolvesThePowerAtTheTerminals)
{
  BatteryConfig c;
  c.resistance = 0.05;
  for (const double power : {0.0, 50.0, 200.0, 800.0}) {
    Battery b(c);
    const double ocv = b.openCircuitVoltage();
    b.draw(power, 0.001);
    // V I = P and V = OCV − I R, the root with the higher voltage.
    EXPECT_NEAR(b.voltage() * b.current(), power, 1e-9 * (1.0 + power));
    EXPECT_NEAR(b.voltage(), ocv - b.current() * c.resistance, 1e-12);
    EXPECT_GT(b.voltage(), ocv / 2.0);
  }
  // More than OCV² / 4R: the most the pack gives, at half its voltage.
  Battery b(c);
  const double ocv = b.openCircuitVoltage();
  b.draw(ocv * ocv / (4.0 * c.resistance) * 1.5, 0.001);
  EXPECT_NEAR(b.current(), ocv / (2.0 * c.resistance), 1e-9);
  EXPECT_NEAR(b.voltage(), ocv / 2.0, 1e-9);
}

TEST(Battery, ChargeFallsByTheIntegralOfTheCurrent)
{
  BatteryConfig c;
  c.capacity = 5.0;
  c.resistance = 0.0;  // I = P / OCV
  Battery b(c);
  double ampere_seconds = 0.0;
  for (int k = 0; k < 36000; ++k) {  // an hour in 0.1 s steps, 60 W
    b.draw(60.0, 0.1);
    ampere_seconds += b.current() * 0.1;
    ASSERT_NEAR(b.current(), 60.0 / b.voltage(), 1e-9);
  }
  EXPECT_NEAR((c.capacity - b.chargeAh()) * 3600.0, ampere_seconds, 1e-6);
  EXPECT_NEAR(b.energyDrawn(), 60.0 * 3600.0, 1e-3);  // 60 Wh of a 4S 5 Ah pack's 75 or so
  EXPECT_FALSE(b.empty());
  EXPECT_LT(b.charge(), 0.25);
  // Drawn on until empty: then it gives nothing, and the rotors get no supply.
  for (int k = 0; k < 36000 && !b.empty(); ++k) {
    b.draw(600.0, 0.1);
  }
  EXPECT_TRUE(b.empty());
  EXPECT_DOUBLE_EQ(b.supply(), 0.0);
  b.draw(600.0, 0.1);
  EXPECT_DOUBLE_EQ(b.current(), 0.0);
}

TEST(Battery, AFailedCellTakesItsShareOfTheVoltage)
{
  BatteryConfig c;
  c.cells = 4;
  Battery b(c);
  const double full = b.openCircuitVoltage();
  EXPECT_DOUBLE_EQ(full, 4 * 4.2);
  b.loseCells(1);
  EXPECT_EQ(b.workingCells(), 3);
  EXPECT_DOUBLE_EQ(b.openCircuitVoltage(), 3 * 4.2);
  b.loseCells(9);  // no fewer than none
  EXPECT_EQ(b.workingCells(), 0);
  EXPECT_TRUE(b.empty());
}

TEST(Battery, SupplyIsWholeDownToTheRatedVoltageThenFollowsIt)
{
  BatteryConfig c;
  c.resistance = 0.0;
  c.rated_cell_voltage = 3.7;
  Battery b(c);
  b.draw(10.0, 0.001);
  EXPECT_DOUBLE_EQ(b.supply(), 1.0);  // 16.8 V > 14.8 V
  b.loseCells(1);                     // 12.6 V
  b.draw(10.0, 0.001);
  EXPECT_NEAR(b.supply(), b.voltage() / (4 * 3.7), 1e-12);
  EXPECT_LT(b.supply(), 0.86);
}

TEST(Battery, PowerIsTheRotorsShaftPowerOverTheEfficiencyPlusTheAvionics)
{
  BatteryConfig c;
  c.motor_efficiency = 0.8;
  c.avionics_power = 6.0;
  const Battery b(c);
  const double km = 1.4e-7;
  const RotorArray w{500.0, 500.0, 500.0, 500.0};
  EXPECT_NEAR(b.powerFor(w, {1.0, 1.0, 1.0, 1.0}, km), 4 * km * 500.0 * 500.0 * 500.0 / 0.8 + 6.0, 1e-9);
  // A rotor with half its thrust left turns the air with half the torque.
  EXPECT_NEAR(b.powerFor(w, {1.0, 0.5, 1.0, 1.0}, km), 3.5 * km * 500.0 * 500.0 * 500.0 / 0.8 + 6.0, 1e-9);
}

TEST(Battery, ConfigOutOfRangeIsRefused)
{
  const auto with = [](auto change) {
    BatteryConfig c;
    change(c);
    return c;
  };
  EXPECT_THROW(Battery(with([](BatteryConfig& c) { c.cells = 0; })), std::invalid_argument);
  EXPECT_THROW(Battery(with([](BatteryConfig& c) { c.capacity = 0.0; })), std::invalid_argument);
  EXPECT_THROW(Battery(with([](BatteryConfig& c) { c.initial_charge = 1.2; })), std::invalid_argument);
  EXPECT_THROW(Battery(with([](BatteryConfig& c) { c.resistance = -0.1; })), std::invalid_argument);
  EXPECT_THROW(Battery(with([](BatteryConfig& c) { c.motor_efficiency = 0.0; })), std::invalid_argument);
}

/// A vehicle on the ground in an empty box, its rotors commanded to `w`.
struct Bench {
  explicit Bench(BatteryConfig battery, std::vector<Fault> faults = {})
      : sim(vehicle::VehicleParams{},
            world::World(world::Bounds{Vector3(-5, -5, 0), Vector3(5, 5, 5)}, Vector3(0, 0, 0), Vector3(1, 0, 0), {}),
            config(battery), std::move(faults))
  {
  }
  static SimulationConfig config(BatteryConfig battery)
  {
    SimulationConfig c;
    c.battery = battery;
    c.depth.rate_hz = 0.0;
    return c;
  }
  void run(double seconds, double w)
  {
    const auto steps = static_cast<int>(std::lround(seconds / 0.001));
    for (int k = 0; k < steps; ++k) {
      sim.commands().submit({w, w, w, w}, true, sim.timeNs(), sim.timeNs());
      sim.step();
    }
  }
  Simulation sim;
};

TEST(Battery, TheSimulationDrawsTheRotorsPowerFromThePack)
{
  BatteryConfig c;
  c.resistance = 0.0;
  c.avionics_power = 5.0;
  c.motor_efficiency = 0.75;
  Bench bench(c);
  const double w = 300.0;  // too slow to lift off: the vehicle stays on the ground
  bench.run(1.0, w);       // the motors spin up (time constants of tens of ms)
  const double before = bench.sim.battery()->energyDrawn();
  bench.run(10.0, w);
  const double km = bench.sim.dynamics().params().torque_coefficient;
  const double power = 4.0 * km * w * w * w / 0.75 + 5.0;
  EXPECT_NEAR(bench.sim.battery()->energyDrawn() - before, power * 10.0, 1e-6 * power * 10.0);
  EXPECT_TRUE(bench.sim.state().landed);
}

TEST(Battery, ASaggingPackCapsTheRotorsTopSpeed)
{
  BatteryConfig c;
  c.resistance = 0.0;
  c.avionics_power = 0.0;
  Bench bench(c, {Fault{.id = 1, .kind = Fault::Kind::kCellLoss, .cells = 2, .start_ns = 100'000'000}});
  const double top = bench.sim.dynamics().params().rotor_speed_max;
  bench.run(0.05, 0.0);
  EXPECT_EQ(bench.sim.battery()->workingCells(), 4);
  bench.run(0.1, 0.0);
  EXPECT_EQ(bench.sim.battery()->workingCells(), 2);
  // Full throttle on two cells of four: the speed controllers reach the voltage's share of
  // the rated top speed, and the thrust its square.
  bench.run(1.0, top);
  const double supply = bench.sim.battery()->voltage() / (4 * c.rated_cell_voltage);
  EXPECT_NEAR(supply, 2 * cellOpenCircuitVoltage(bench.sim.battery()->charge()) / 14.8, 1e-5);  // one step's drain
  for (const double w : bench.sim.state().rotor_speed) {
    EXPECT_NEAR(w, supply * top, 1e-3 * top);
  }
}

}  // namespace
}  // namespace quad::plant
