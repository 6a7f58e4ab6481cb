// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Follows a scenario's timeline while it runs: says which steps are due, takes what the
/// stack did (modes, liveliness, restarts, rejected inputs), measures each reaction from the
/// moment its fault took effect, and gives the verdict as a pass/fail table. No DDS: the
/// fault command feeds it.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "quad/fault/scenario.hpp"

namespace quad::fault {

/// What the run left behind, for the outcome checks.
struct RunFacts {
  bool mission_known = false;      ///< the manifest flew a mission and it was followed
  bool mission_success = false;
  std::string mission_outcome;     ///< "landed at the goal", ...
  std::string mission_end;         ///< the summary's end: "success", "failed", "no_path", "crashed", ...
  /// A fleet's run: each vehicle's mission, its success and outcome in words.
  std::map<std::uint32_t, std::pair<bool, std::string>> vehicle_missions;
  int collisions = 0;
  std::uint64_t actuator_commands = 0;
  std::uint64_t nonfinite_actuator_commands = 0;
  std::string run_failure;         ///< a module failed outside the scenario's faults; empty if none
  /// Missing + duplicated + reordered samples per reliable topic of the recording whose
  /// writers keep more than their newest sample.
  std::map<std::string, std::uint64_t> reliable_loss;
  /// Reliable topics whose writers keep only their newest sample (not judged).
  std::size_t latest_only_topics = 0;
  std::string recording_problem;   ///< why the recording could not be read; empty if it could
  /// Samples the modules' own readers lost on topics that promise every sample (their
  /// heartbeats' count, summed over each module's processes), by manifest module.
  std::map<std::string, std::uint64_t> module_loss;
};

class Judge {
public:
  explicit Judge(const Scenario& scenario);

  /// Steps due at sim time `t` not handed out yet, in order; the caller applies each and
  /// reports applied() or refused().
  std::vector<std::size_t> due(double t);
  /// The step's fault took effect at sim time `t`, wall time `wall_ns` (steady clock).
  void applied(std::size_t step, double t, std::int64_t wall_ns, const std::string& detail);
  /// The step's fault could not be applied.
  void refused(std::size_t step, const std::string& why);
  bool isApplied(std::size_t step) const { return steps_.at(step).applied; }
  /// The step's fault (one that lasts: datagram faults) ended at sim time `t` (acknowledged).
  void cleared(std::size_t step, double t, const std::string& detail);

  /// Time passed: expectations whose bound is over fail.
  void clock(double t, std::int64_t wall_ns);
  /// The vehicle was at altitude `z` [m] at sim time `t`.
  void altitude(double t, double z);
  /// The controller reported `mode` at sim time `t`.
  void mode(double t, const std::string& mode);
  /// A path a controller would fly (PLAN_OK, finite waypoints) stamped at sim time `t`; feed
  /// those of a batch before its modes.
  void path(double t);
  /// The launcher saw `module`'s writers lose liveliness.
  void lost(const std::string& module, std::int64_t wall_ns);
  /// `module` runs again: a heartbeat from a process it was not before.
  void back(const std::string& module, std::int64_t wall_ns);
  /// The launcher ended the run because `module` (ends_run) exited.
  void runEnded(const std::string& module, std::int64_t wall_ns);
  /// `module`'s count of rejected inputs grew.
  void rejected(const std::string& module, std::int64_t wall_ns);
  /// The estimator's count of refused `sensor` samples grew, in its state stamped at sim time `t`.
  void outliers(const std::string& sensor, double t);

  /// Every step applied (or refused) and every expectation decided.
  bool settled() const;

  struct Row {
    std::string step;         ///< "1", or "end" for the outcome
    std::string fault;        ///< "t=12.0 kill planning" on the step's first row
    std::string expectation;  ///< "mode HOVER"
    std::string bound;        ///< "<= 0.50 s (sim)"
    std::string measured;     ///< "0.31 s", "not seen", ...
    bool pass = false;
    std::optional<double> within_s;    ///< a reaction's time bound [s]
    std::optional<double> measured_s;  ///< the reaction's measured time [s], when it came
  };
  /// The verdict, once the run is over: pending expectations fail, then the outcome checks.
  std::vector<Row> finish(const RunFacts& facts);

private:
  struct Pending {
    Expectation expect;
    std::optional<double> measured_s;  // met, after this long
    bool failed = false;
    std::string why;                   // when failed
    std::optional<double> z0;          // kAltitudeLost: the altitude at the fault
    double drop = 0.0;                 // kAltitudeLost: the most lost so far [m]
  };
  struct StepState {
    bool handed_out = false;
    bool applied = false;
    std::string refusal;
    double t = 0.0;
    std::int64_t wall_ns = 0;
    std::string detail;
    std::optional<double> cleared_t;
    std::string cleared_detail;
    std::vector<Pending> pending;
  };
  void meet(std::size_t step, Expectation::Kind kind, const std::string& subject, double measured_s);
  /// A kMode expectation's reference time: its step's fault, or the last path.
  double modeOrigin(const StepState& s, const Pending& p) const;
  /// An event at sim time `t`, measured from every step applied (a mode: at once if already in it).
  void meetAt(Expectation::Kind kind, const std::string& subject, double t);
  /// A module's event at wall time `wall_ns`, measured from every step applied before it.
  void meetAfter(Expectation::Kind kind, const std::string& module, std::int64_t wall_ns);

  const Scenario& scenario_;
  std::vector<StepState> steps_;
  std::string mode_;
  double t_ = 0.0;
  std::optional<double> last_path_t_;  // sim time of the last path a controller would fly
};

/// The rows as an aligned table, PASS/FAIL in the last column, and a last line with the verdict.
std::string toTable(const std::string& scenario_name, const std::vector<Judge::Row>& rows);

/// The verdict as one JSON object (`fault_report.json`): the scenario, whether it passed,
/// and the rows (`step`, `fault`, `expectation`, `bound`, `measured`, `pass`, and for a
/// reaction `within_s` and `measured_s`, null when it did not come).
std::string toJson(const std::string& scenario_name, const std::vector<Judge::Row>& rows);

/// True when every row passed.
bool passed(const std::vector<Judge::Row>& rows);

}  // namespace quad::fault
