// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// What a recording says of a flight, in the report's terms: the true and estimated
/// trajectories, the goal, every path the planner published, the controller's modes and
/// errors, the simulator's and the fault tool's events, the mapper's last map and each
/// topic's rate. Messages are decoded with the schemas the recording carries, so a recording
/// made by another build of quad reads as long as the fields the report uses are there.

#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "quad/bag/mcap.hpp"
#include "quad/geometry/so3.hpp"
#include "quad/launch/estimate_score.hpp"

namespace quad::report {

using geometry::Vector3;

/// A recording that lacks what the report needs, or a message that does not decode: names
/// the topic and the problem.
class FlightError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct FlightData {
  struct State {
    double t_s = 0.0;  ///< [s] sim time (the sample's stamp)
    Vector3 p_W;
    Vector3 v_W;
  };
  struct Goal {
    double t_s = 0.0;
    Vector3 p_W;
    double tolerance_m = 0.0;
  };
  struct Path {
    double t_s = 0.0;
    std::uint32_t version = 0;
    std::string status;  ///< PlanStatus enumerator
    std::vector<Vector3> waypoints_W;
    std::uint64_t expansions = 0;
    double replan_time_s = 0.0;
  };
  struct Status {
    double t_s = 0.0;
    std::string mode;      ///< ControlMode enumerator
    std::string failsafe;  ///< FailsafeReason enumerator
    double position_error_m = 0.0;
    double attitude_error_deg = 0.0;
  };
  struct Event {
    double t_s = 0.0;
    std::string kind;  ///< SimEventKind enumerator
    std::string detail;
    bool from_fault_tool = false;  ///< published by the fault tool (quad/system/fault_events)
  };
  struct TopicRate {
    std::string topic;
    std::uint64_t messages = 0;
    double rate_hz = 0.0;                 ///< per writer, over the sim time its own stamps span
    std::optional<double> contract_hz;    ///< the recorded channel's rate_hz, when periodic
    int writers = 1;                      ///< as the recorder counted them (quad.loss)
  };

  std::vector<State> truth;     ///< quad/sim/state, one sample per 40 ms of sim time
  std::vector<State> estimate;  ///< quad/estimation/state (aligned samples), likewise
  std::vector<Goal> goals;
  std::vector<Path> paths;
  std::vector<Status> status;
  std::vector<Event> events;
  std::vector<TopicRate> rates;
  std::vector<Vector3> occupied_W;  ///< centres of the last map snapshot's occupied voxels
  double map_resolution_m = 0.0;    ///< 0: no snapshot recorded
  std::vector<launch::EstimateErrorPoint> estimate_error;  ///< empty without an estimator
  double t_first_s = 0.0;  ///< sim time spanned by the vehicle's state
  double t_last_s = 0.0;
  std::uint64_t messages = 0;
};

/// Called now and then while the messages are decoded: how many of how many are done.
using Progress = std::function<void(std::size_t done, std::size_t total)>;

/// Reads a recording's flight: of `vehicle` alone (Header.vehicle_id; the fault tool's events
/// are every vehicle's), or, when none is given, of the one vehicle the recording holds. Throws
/// FlightError when the recording holds no vehicle state (quad/sim/state) of it, states of
/// several vehicles and no `vehicle` (naming them), or a message the report uses does not
/// decode.
FlightData readFlight(const bag::McapContents& recording, const Progress& progress = {},
                      std::optional<std::uint32_t> vehicle = std::nullopt);

}  // namespace quad::report
