// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "quad/common/time.hpp"

namespace quad::plant {

Simulation::Simulation(vehicle::VehicleParams vehicle, world::World world, SimulationConfig config,
                       std::vector<Fault> schedule)
    : dynamics_(vehicle),
      world_(std::move(world)),
      config_(std::move(config)),
      camera_(config_.depth),
      guard_(vehicle, config_.command_timeout_ns, config_.command_failsafe_ns),
      rng_(config_.seed),
      wind_(config_.wind, config_.seed ^ 0x9e3779b97f4a7c15ULL),
      nav_rng_(config_.seed ^ 0x6a09e667f3bcc909ULL),
      imu_bias_(turnOnBias(config_.imu, nav_rng_)),
      position_(config_.position),
      baro_(config_.baro, nav_rng_),
      range_down_{&SimulationConfig::range, Sensor::kRange, kDownward,
                  std::mt19937_64(config_.seed ^ 0x3c6ef372fe94f82bULL)},
      range_up_{&SimulationConfig::range_up, Sensor::kRangeUp, kUpward,
                std::mt19937_64(config_.seed ^ 0xa54ff53a5f1d36f1ULL)}
{
  // RK4 is stable on the motor lag only while step/τ stays inside its region (2.78): keep a
  // margin, and refuse a vehicle whose motors are too fast for the step.
  const double step_s = common::toSeconds(config_.step_ns);
  const double fastest = std::min(vehicle.motor_time_constant_up, vehicle.motor_time_constant_down);
  if (fastest < 0.4 * step_s) {
    throw std::invalid_argument("motor time constant " + std::to_string(fastest) + " s is below 0.4 x the step " +
                                std::to_string(step_s) + " s: RK4 would be unstable; shorten sim.step");
  }
  state_.p_W = world_.start();
  surface_z_ = world_.supportHeight(state_.p_W, dynamics_.params().radius);
  state_.landed = state_.p_W.z() <= surface_z_;
  state_.p_W.z() = std::max(surface_z_, state_.p_W.z());
  if (config_.gimbal.enabled) {
    gimbal_.emplace(config_.gimbal, 0.0, 0.0);  // level, along world x: the vehicle starts level at yaw 0
  }
  if (config_.battery.enabled) {
    battery_.emplace(config_.battery);
  }
  for (auto& f : schedule) {
    injectFault(f);
  }
  // Samples fall on each rate's grid: k × period.
  const auto first = [](double rate_hz) {
    return rate_hz > 0.0 ? static_cast<std::int64_t>(std::llround(1e9 / rate_hz)) : 0;
  };
  next_state_ns_ = first(config_.state_rate_hz);
  next_imu_ns_ = first(config_.imu.rate_hz);
  next_depth_ns_ = first(config_.depth.rate_hz);
  next_battery_ns_ = first(config_.battery_rate_hz);
  next_position_ns_ = config_.position.enabled ? first(config_.position.rate_hz) : 0;
  next_baro_ns_ = config_.baro.enabled ? first(config_.baro.rate_hz) : 0;
  next_mag_ns_ = config_.mag.enabled ? first(config_.mag.rate_hz) : 0;
}

bool Simulation::aimGimbal(double yaw_W, double pitch)
{
  return gimbal_ && gimbal_->aim(yaw_W, pitch);
}

geometry::Pose3 Simulation::cameraPose() const
{
  const geometry::Pose3 body_W{state_.p_W, state_.q_WB};
  if (!gimbal_) {
    return camera_.sensorPose(body_W);
  }
  return {body_W.transform(config_.depth.position_B), gimbal_->orientation_W()};
}

bool Simulation::injectFault(Fault fault)
{
  const bool known = std::any_of(faults_.begin(), faults_.end(),
                                 [&](const Active& a) { return a.fault.id == fault.id; });
  if (known) {
    return false;
  }
  faults_.push_back({fault, false});
  return true;
}

bool Simulation::clearFault(std::uint32_t id)
{
  for (auto& a : faults_) {
    if (a.fault.id == id) {
      // Expire it at the next step, which reports the clearing.
      a.fault.start_ns = std::min(a.fault.start_ns, t_ns_);
      a.fault.duration_ns = std::max<std::int64_t>(1, t_ns_ - a.fault.start_ns);
      return true;
    }
  }
  return false;
}

void Simulation::setState(const RigidBodyState& state)
{
  state_ = state;
  surface_z_ = world_.supportHeight(state_.p_W, dynamics_.params().radius);
  imu_integrals_.restart();  // a state set is not a motion the IMU felt
}

Environment Simulation::environment() const
{
  Environment env;
  env.gravity_W = config_.gravity_W;
  env.wind_W = wind_.current();
  env.supply = battery_ ? battery_->supply() : 1.0;
  env.ground_z = surface_z_;
  for (const auto& a : faults_) {
    if (!a.applied) {
      continue;
    }
    if (a.fault.kind == Fault::Kind::kMotor) {
      env.rotor_efficiency[static_cast<std::size_t>(a.fault.rotor)] *= a.fault.magnitude;
    } else if (a.fault.kind == Fault::Kind::kWindGust) {
      env.wind_W += a.fault.wind_W;
    } else if (a.fault.kind == Fault::Kind::kPush) {
      env.force_W += a.fault.force_W;
    }
  }
  return env;
}

bool Simulation::sensorFault(Sensor s, Fault::Kind k) const
{
  return std::any_of(faults_.begin(), faults_.end(), [&](const Active& a) {
    return a.applied && a.fault.kind == k && a.fault.sensor == s;
  });
}

template <typename T>
T Simulation::sumOfFaults(Sensor s, Fault::Kind k, T Fault::*field, T zero) const
{
  for (const auto& a : faults_) {
    if (a.applied && a.fault.kind == k && a.fault.sensor == s) {
      zero += a.fault.*field;
    }
  }
  return zero;
}

double Simulation::sensorNoise(Sensor s) const
{
  return sumOfFaults(s, Fault::Kind::kSensorNoise, &Fault::magnitude, 0.0);
}

Vector3 Simulation::sensorOffset(Sensor s) const
{
  return sumOfFaults<Vector3>(s, Fault::Kind::kSensorOffset, &Fault::offset, Vector3::Zero());
}

void Simulation::applyFaults(StepOutputs& out)
{
  for (auto it = faults_.begin(); it != faults_.end();) {
    const Fault& f = it->fault;
    if (!it->applied && t_ns_ >= f.start_ns) {
      it->applied = true;
      if (f.kind == Fault::Kind::kCellLoss && battery_) {
        battery_->loseCells(f.cells);  // for good: a clearing ends only the record
      }
      out.events.push_back({SimEventRecord::Kind::kFaultApplied, t_ns_, state_.p_W, f.id, f.describe()});
    }
    if (it->applied && f.duration_ns > 0 && t_ns_ >= f.start_ns + f.duration_ns) {
      out.events.push_back({SimEventRecord::Kind::kFaultCleared, t_ns_, state_.p_W, f.id, f.describe()});
      it = faults_.erase(it);
      continue;
    }
    ++it;
  }
}

bool Simulation::due(std::int64_t t_ns, std::int64_t& next_ns, double rate_hz)
{
  if (rate_hz <= 0.0 || t_ns < next_ns) {
    return false;
  }
  const auto period = static_cast<std::int64_t>(std::llround(1e9 / rate_hz));
  // The next sample on the period's grid after t (a slow step never bursts samples).
  next_ns = (t_ns / period + 1) * period;
  return true;
}

void Simulation::measureNavigation(StepOutputs& out)
{
  // Each as the IMU: a dropout fault sends nothing, a stuck one repeats the last content with
  // fresh stamps, a noise fault adds to the white noise, an offset fault to the reading (a
  // position jump, a barometer step, a magnetic disturbance).
  const auto live = [&](Sensor s) { return !sensorFault(s, Fault::Kind::kSensorDropout); };
  const auto fresh = [&](Sensor s, const auto& last) { return !sensorFault(s, Fault::Kind::kSensorStuck) || !last; };
  if (config_.position.enabled && due(t_ns_, next_position_ns_, config_.position.rate_hz) && live(Sensor::kPosition)) {
    if (fresh(Sensor::kPosition, last_position_)) {
      if (const auto fix = position_.measure(state_.p_W + sensorOffset(Sensor::kPosition), nav_rng_,
                                             sensorNoise(Sensor::kPosition))) {
        last_position_ = PositionReading{t_ns_, *fix};
        positions_in_flight_.push_back(*last_position_);
      }
    } else {
      last_position_->t_ns = t_ns_;
      positions_in_flight_.push_back(*last_position_);
    }
  }
  const auto latency_ns = common::toNanoseconds(config_.position.latency);
  if (!positions_in_flight_.empty() && positions_in_flight_.front().t_ns + latency_ns <= t_ns_) {
    out.position = positions_in_flight_.front();
    positions_in_flight_.pop_front();
  }
  if (config_.baro.enabled && due(t_ns_, next_baro_ns_, config_.baro.rate_hz) && live(Sensor::kBaro)) {
    if (fresh(Sensor::kBaro, last_baro_)) {
      last_baro_ = BaroReading{t_ns_, baro_.measure(state_.p_W.z() + sensorOffset(Sensor::kBaro).z(), 1.0 / config_.baro.rate_hz,
                                                    nav_rng_, sensorNoise(Sensor::kBaro)),
                               config_.baro.noise_std};
    }
    last_baro_->t_ns = t_ns_;
    out.baro = last_baro_;
  }
  if (config_.mag.enabled && due(t_ns_, next_mag_ns_, config_.mag.rate_hz) && live(Sensor::kMag)) {
    if (fresh(Sensor::kMag, last_mag_)) {
      last_mag_ = MagReading{t_ns_, measureMagnetometer(config_.mag, state_.q_WB, sensorOffset(Sensor::kMag), nav_rng_,
                                                        sensorNoise(Sensor::kMag)),
                             config_.mag.noise_std};
    }
    last_mag_->t_ns = t_ns_;
    out.mag = last_mag_;
  }
  // The rangefinders read at turn-on (the first step), then on their grid: a controller knows
  // what the vehicle stands on, and what is over it, from its first state on.
  out.range = measureRangefinder(range_down_);
  out.range_up = measureRangefinder(range_up_);
}

std::optional<RangeReading> Simulation::measureRangefinder(Rangefinder& r)
{
  const RangefinderConfig& config = config_.*r.config;
  if (!config.enabled || !due(t_ns_, r.next_ns, config.rate_hz) || sensorFault(r.sensor, Fault::Kind::kSensorDropout)) {
    return std::nullopt;
  }
  if (!sensorFault(r.sensor, Fault::Kind::kSensorStuck) || !r.last) {
    auto range = measureRange(config, world_, state_.p_W, state_.q_WB, r.axis_B, r.rng, sensorNoise(r.sensor));
    if (range) {
      *range = std::max(0.0, *range + sensorOffset(r.sensor).z());
    }
    r.last = RangeReading{t_ns_, range, config.max_range, config.noise_std};
  }
  r.last->t_ns = t_ns_;
  return r.last;
}

StepOutputs Simulation::step()
{
  StepOutputs out;
  const RotorArray command = guard_.command(t_ns_);
  wind_.step(state_.p_W, state_.v_W, common::toSeconds(config_.step_ns));
  const Environment env = environment();
  const bool was_landed = state_.landed;
  const Vector3 v_before = state_.v_W;
  const geometry::Matrix3 R_before = geometry::toMatrix(state_.q_WB);
  if (!crash_) {
    dynamics_.step(state_, command, env, common::toSeconds(config_.step_ns));
    surface_z_ = world_.supportHeight(state_.p_W, dynamics_.params().radius);
  }
  if (battery_) {
    battery_->draw(battery_->powerFor(state_.rotor_speed, env.rotor_efficiency, dynamics_.params().torque_coefficient),
                   common::toSeconds(config_.step_ns));
  }
  if (gimbal_) {
    gimbal_->step(common::toSeconds(config_.step_ns));
  }
  t_ns_ += config_.step_ns;
  applyFaults(out);

  if (was_landed != state_.landed) {
    out.events.push_back({state_.landed ? SimEventRecord::Kind::kGroundContact : SimEventRecord::Kind::kTakeoff,
                          t_ns_, state_.p_W, -1, state_.landed ? "landed" : "took off"});
  }
  // A collision is the start of a contact with a solid (or the bounds). An impact with a solid
  // stops the vehicle where it is: it has crashed, and holds still from then on.
  const std::vector<int> now = world_.contacts(state_.p_W, dynamics_.params().radius, surface_z_);
  for (const int id : now) {
    if (!std::binary_search(contacts_.begin(), contacts_.end(), id)) {
      ++collisions_;
      out.events.push_back({SimEventRecord::Kind::kCollision, t_ns_, state_.p_W, id,
                            id == world::World::kBounds ? "left the bounds" : "hit " + world_.describe(id)});
      if (config_.crash_on_impact && id != world::World::kBounds && !crash_) {
        crash_ = Crash{t_ns_, state_.v_W.norm(), id};
        out.events.push_back({SimEventRecord::Kind::kCrash, t_ns_, state_.p_W, id,
                              fmt::format("crashed into {} at {:.2f} m/s", world_.describe(id), crash_->speed)});
        state_.v_W.setZero();
        state_.w_B.setZero();
        state_.rotor_speed.fill(0.0);
      }
    }
  }
  contacts_ = now;

  const Environment after = environment();
  out.state_due = due(t_ns_, next_state_ns_, config_.state_rate_hz);
  if (out.state_due && !sensorFault(Sensor::kState, Fault::Kind::kSensorDropout)) {
    if (!sensorFault(Sensor::kState, Fault::Kind::kSensorStuck) || !last_state_) {
      last_state_ = StateSample{t_ns_, state_, dynamics_.acceleration(state_, after)};
      if (const double extra = sensorNoise(Sensor::kState); extra > 0.0) {
        // A noise fault on the state: position [m] and velocity [m/s] get white noise.
        std::normal_distribution<double> n(0.0, extra);
        for (int a = 0; a < 3; ++a) {  // one draw at a time: a fixed order, reproducible
          last_state_->state.p_W[a] += n(rng_);
        }
        for (int a = 0; a < 3; ++a) {
          last_state_->state.v_W[a] += n(rng_);
        }
      }
    }
    last_state_->t_ns = t_ns_;  // stuck: the content freezes, the samples keep coming
    out.state = last_state_;
  }
  const bool imu_due = due(t_ns_, next_imu_ns_, config_.imu.rate_hz);
  imu_integrals_.addStep(R_before, state_.v_W - v_before, env.gravity_W, common::toSeconds(config_.step_ns));
  const std::optional<ImuIntegrals::Means> felt = imu_due ? imu_integrals_.sample(state_.q_WB) : std::nullopt;
  if (imu_due && !sensorFault(Sensor::kImu, Fault::Kind::kSensorDropout)) {
    if (!sensorFault(Sensor::kImu, Fault::Kind::kSensorStuck) || !last_imu_) {
      walkBias(imu_bias_, config_.imu, 1.0 / config_.imu.rate_hz, nav_rng_);
      ImuBias bias = imu_bias_;
      bias.accel += sensorOffset(Sensor::kImu);  // a bias step
      // Integrated over the sample period (ImuIntegrals); the first sample reads the instant.
      const ImuIntegrals::Means means =
          felt ? *felt
               : ImuIntegrals::Means{geometry::toMatrix(state_.q_WB).transpose() *
                                         (dynamics_.acceleration(state_, after) - after.gravity_W),
                                     state_.w_B};
      last_imu_ = ImuReading{t_ns_, measureImuIntegrals(config_.imu, bias, means.force_B, means.w_B, rng_,
                                                        sensorNoise(Sensor::kImu))};
    }
    last_imu_->t_ns = t_ns_;
    out.imu = last_imu_;
  }
  measureNavigation(out);
  if (due(t_ns_, next_depth_ns_, config_.depth.rate_hz) &&
      !sensorFault(Sensor::kDepth, Fault::Kind::kSensorDropout)) {
    if (!sensorFault(Sensor::kDepth, Fault::Kind::kSensorStuck) || !last_depth_) {
      const geometry::Pose3 sensor_W = cameraPose();
      last_depth_ = DepthReading{t_ns_, camera_.captureFrom(world_, sensor_W, rng_, sensorNoise(Sensor::kDepth), others_),
                                 geometry::Pose3{state_.p_W, state_.q_WB}.inverse() * sensor_W};
    }
    last_depth_->t_ns = t_ns_;
    out.depth = last_depth_;
  }
  if (battery_ && due(t_ns_, next_battery_ns_, config_.battery_rate_hz)) {
    out.battery = BatteryReading{t_ns_,
                                 battery_->voltage(),
                                 battery_->current(),
                                 battery_->charge(),
                                 battery_->config().capacity,
                                 battery_->config().cells};
  }
  return out;
}

}  // namespace quad::plant
