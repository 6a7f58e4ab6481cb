// SPDX-License-Identifier: BSD-3-Clause
#include "quad/fault/judge.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "quad/common/time.hpp"
#include "quad/launch/mission.hpp"

namespace quad::fault {

Judge::Judge(const Scenario& scenario) : scenario_(scenario), steps_(scenario.steps.size())
{
  for (std::size_t i = 0; i < steps_.size(); ++i) {
    for (const auto& e : scenario.steps[i].expect) {
      steps_[i].pending.push_back({e, std::nullopt, false, ""});
    }
  }
}

std::vector<std::size_t> Judge::due(double t)
{
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < steps_.size(); ++i) {
    if (!steps_[i].handed_out && scenario_.steps[i].at_s <= t) {
      steps_[i].handed_out = true;
      out.push_back(i);
    }
  }
  return out;
}

void Judge::applied(std::size_t step, double t, std::int64_t wall_ns, const std::string& detail)
{
  StepState& s = steps_.at(step);
  s.applied = true;
  s.t = t;
  s.wall_ns = wall_ns;
  s.detail = detail;
  // A mode the controller is already in is reached at once.
  meet(step, Expectation::Kind::kMode, mode_, 0.0);
}

void Judge::refused(std::size_t step, const std::string& why)
{
  StepState& s = steps_.at(step);
  s.refusal = why;
  for (auto& p : s.pending) {
    p.failed = true;
    p.why = "the fault was not applied";
  }
}

void Judge::cleared(std::size_t step, double t, const std::string& detail)
{
  StepState& s = steps_.at(step);
  s.cleared_t = t;
  s.cleared_detail = detail;
}

double Judge::modeOrigin(const StepState& s, const Pending& p) const
{
  return p.expect.since == Expectation::Since::kLastPath && last_path_t_ ? *last_path_t_ : s.t;
}

void Judge::meet(std::size_t step, Expectation::Kind kind, const std::string& subject, double measured_s)
{
  const StepState& s = steps_[step];
  for (auto& p : steps_[step].pending) {
    const std::string& want = kind == Expectation::Kind::kMode ? p.expect.mode : p.expect.module;
    if (p.expect.kind != kind || want != subject || p.measured_s || p.failed) {
      continue;
    }
    // measured_s is from the fault; a mode bound may count from elsewhere.
    const double measured = kind == Expectation::Kind::kMode ? std::max(0.0, s.t + measured_s - modeOrigin(s, p))
                                                             : measured_s;
    if (measured <= p.expect.within_s) {
      p.measured_s = measured;
    } else {
      p.failed = true;
      p.why = fmt::format("{:.3f} s", measured);
    }
  }
}

void Judge::clock(double t, std::int64_t wall_ns)
{
  t_ = std::max(t_, t);
  for (auto& s : steps_) {
    if (!s.applied) {
      continue;
    }
    for (auto& p : s.pending) {
      if (p.measured_s || p.failed) {
        continue;
      }
      const double elapsed = p.expect.simTime() ? t - modeOrigin(s, p) : common::toSeconds(wall_ns - s.wall_ns);
      if (elapsed <= p.expect.within_s) {
        continue;
      }
      if (p.expect.kind == Expectation::Kind::kAltitudeLost && p.z0) {
        p.measured_s = elapsed;  // the window is over, within the bound all along
      } else {
        p.failed = true;
        p.why = "not seen";
      }
    }
  }
}

void Judge::mode(double t, const std::string& mode)
{
  mode_ = mode;
  meetAt(Expectation::Kind::kMode, mode, t);
}

void Judge::outliers(const std::string& sensor, double t) { meetAt(Expectation::Kind::kOutliers, sensor, t); }

void Judge::meetAt(Expectation::Kind kind, const std::string& subject, double t)
{
  for (std::size_t i = 0; i < steps_.size(); ++i) {
    if (steps_[i].applied && (kind == Expectation::Kind::kMode || t >= steps_[i].t)) {
      meet(i, kind, subject, std::max(0.0, t - steps_[i].t));
    }
  }
}

void Judge::altitude(double t, double z)
{
  for (auto& s : steps_) {
    if (!s.applied || t < s.t) {
      continue;
    }
    for (auto& p : s.pending) {
      if (p.expect.kind != Expectation::Kind::kAltitudeLost || p.measured_s || p.failed ||
          t - s.t > p.expect.within_s) {
        continue;
      }
      if (!p.z0) {
        p.z0 = z;
      }
      p.drop = std::max(p.drop, *p.z0 - z);
      if (p.drop > p.expect.metres) {
        p.failed = true;
        p.why = fmt::format("{:.2f} m by {:.2f} s", p.drop, t - s.t);
      }
    }
  }
}

void Judge::path(double t)
{
  last_path_t_ = std::max(last_path_t_.value_or(t), t);
}

void Judge::meetAfter(Expectation::Kind kind, const std::string& module, std::int64_t wall_ns)
{
  for (std::size_t i = 0; i < steps_.size(); ++i) {
    if (steps_[i].applied && wall_ns >= steps_[i].wall_ns) {
      meet(i, kind, module, common::toSeconds(wall_ns - steps_[i].wall_ns));
    }
  }
}

void Judge::lost(const std::string& module, std::int64_t wall_ns)
{
  meetAfter(Expectation::Kind::kNoticed, module, wall_ns);
}

void Judge::back(const std::string& module, std::int64_t wall_ns)
{
  meetAfter(Expectation::Kind::kBack, module, wall_ns);
}

void Judge::runEnded(const std::string& module, std::int64_t wall_ns)
{
  meetAfter(Expectation::Kind::kRunEnded, module, wall_ns);
}

void Judge::rejected(const std::string& module, std::int64_t wall_ns)
{
  meetAfter(Expectation::Kind::kRejected, module, wall_ns);
}

bool Judge::settled() const
{
  return std::all_of(steps_.begin(), steps_.end(), [](const StepState& s) {
    return (s.applied || !s.refusal.empty()) &&
           std::all_of(s.pending.begin(), s.pending.end(), [](const Pending& p) { return p.measured_s || p.failed; });
  });
}

namespace {
/// "0 on 8 topics" when nothing was lost anywhere (and something was judged), else the
/// lossy ones: "quad/planning/path 2, ...".
std::pair<bool, std::string> lossFigures(const std::map<std::string, std::uint64_t>& loss, const char* on,
                                         const char* what)
{
  std::uint64_t total = 0;
  std::string lossy;
  for (const auto& [name, n] : loss) {
    total += n;
    if (n > 0) {
      lossy += fmt::format("{}{} {}", lossy.empty() ? "" : ", ", name, n);
    }
  }
  if (total > 0) {
    return {false, lossy};
  }
  return {!loss.empty(), fmt::format("0 {} {} {}", on, loss.size(), what)};
}
}  // namespace

std::vector<Judge::Row> Judge::finish(const RunFacts& facts)
{
  std::vector<Row> rows;
  for (std::size_t i = 0; i < steps_.size(); ++i) {
    const Step& step = scenario_.steps[i];
    const StepState& s = steps_[i];
    Row head;
    head.step = std::to_string(i + 1);
    head.fault = fmt::format("t={:.1f} {}", step.at_s, step.action.describe());
    // The fault itself, applied and acknowledged, is the step's first check.
    head.expectation = "applied";
    if (s.applied) {
      head.measured = fmt::format("at {:.2f} s: {}", s.t, s.detail);
    } else if (!s.refusal.empty()) {
      head.measured = "refused: " + s.refusal;
    } else {
      head.measured = fmt::format("not reached (the run ended at {:.2f} s)", t_);
    }
    head.pass = s.applied;
    rows.push_back(head);
    if (step.action.lasts() && s.applied) {
      // A fault that lasts ends when its time is up, and at the latest when the run ends.
      Row r;
      r.expectation = "cleared";
      const std::optional<double> due =
          step.action.duration_s ? std::optional<double>(step.at_s + *step.action.duration_s) : std::nullopt;
      r.bound = due ? fmt::format("at {:.1f} s", *due) : "at the end";
      if (s.cleared_t) {
        r.measured = fmt::format("at {:.2f} s: {}", *s.cleared_t, s.cleared_detail);
        r.pass = true;
      } else {
        r.measured = "not acknowledged";
      }
      rows.push_back(r);
    }
    for (const auto& p : s.pending) {
      Row r;
      r.expectation = p.expect.describe();
      r.bound = fmt::format("<= {:.2f} s ({})", p.expect.within_s, p.expect.simTime() ? "sim" : "wall");
      const bool altitude = p.expect.kind == Expectation::Kind::kAltitudeLost;
      if (altitude) {
        r.bound = fmt::format("<= {:.2f} m in {:.2f} s (sim)", p.expect.metres, p.expect.within_s);
      } else {
        r.within_s = p.expect.within_s;
        r.measured_s = p.measured_s;
      }
      if (p.measured_s) {
        r.measured = altitude ? fmt::format("{:.2f} m", p.drop) : fmt::format("{:.3f} s", *p.measured_s);
        r.pass = true;
      } else {
        r.measured = p.failed ? p.why : (s.applied ? "not seen before the run ended" : "fault not applied");
      }
      rows.push_back(r);
    }
  }
  const auto end = [&](std::string what, std::string bound, std::string measured, bool pass) {
    rows.push_back({"end", "", std::move(what), std::move(bound), std::move(measured), pass});
  };
  end("no module failed", "", facts.run_failure.empty() ? "none" : facts.run_failure, facts.run_failure.empty());
  const Outcome& o = scenario_.outcome;
  if (o.mission == Outcome::Mission::kCrashed) {
    end("mission ends crashed", "", facts.mission_known ? facts.mission_outcome : "no mission",
        facts.mission_known && facts.mission_end == launch::toString(launch::MissionEnd::kCrashed));
  } else if (o.mission != Outcome::Mission::kAny) {
    const bool want = o.mission == Outcome::Mission::kSuccess;
    end(want ? "mission succeeds" : "mission fails", "", facts.mission_known ? facts.mission_outcome : "no mission",
        facts.mission_known && facts.mission_success == want);
  }
  for (const auto& [vehicle, mission] : o.vehicles) {
    if (mission == Outcome::Mission::kAny) {
      continue;
    }
    const bool want = mission == Outcome::Mission::kSuccess;
    const auto it = facts.vehicle_missions.find(vehicle);
    end(fmt::format("vehicle {}'s mission {}", vehicle, want ? "succeeds" : "fails"), "",
        it == facts.vehicle_missions.end() ? "no mission" : it->second.second,
        it != facts.vehicle_missions.end() && it->second.first == want);
  }
  end("collisions", fmt::format("<= {}", o.max_collisions), std::to_string(facts.collisions),
      facts.collisions <= o.max_collisions);
  if (o.finite_actuators) {
    end("finite actuator commands", "all",
        fmt::format("{} of {} non-finite", facts.nonfinite_actuator_commands, facts.actuator_commands),
        facts.nonfinite_actuator_commands == 0 && facts.actuator_commands > 0);
  }
  if (o.zero_loss) {
    if (!facts.recording_problem.empty()) {
      end("no loss on reliable topics", "0", facts.recording_problem, false);
    } else {
      const auto [lossless, measured] = lossFigures(facts.reliable_loss, "on", "topics");
      end("no loss on reliable topics", "0", measured, lossless);
      if (facts.latest_only_topics > 0) {
        rows.back().measured += fmt::format(" ({} keeping only their newest sample not judged)", facts.latest_only_topics);
      }
    }
    const auto [lossless, measured] = lossFigures(facts.module_loss, "in", "modules");
    end("no loss in the modules' readers", "0", measured, lossless);
  }
  return rows;
}

std::string toJson(const std::string& scenario_name, const std::vector<Judge::Row>& rows)
{
  nlohmann::ordered_json j;
  j["scenario"] = scenario_name;
  j["passed"] = passed(rows);
  j["rows"] = nlohmann::ordered_json::array();
  const auto optional = [](const std::optional<double>& v) { return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr); };
  for (const auto& r : rows) {
    j["rows"].push_back({{"step", r.step},
                         {"fault", r.fault},
                         {"expectation", r.expectation},
                         {"bound", r.bound},
                         {"measured", r.measured},
                         {"pass", r.pass},
                         {"within_s", optional(r.within_s)},
                         {"measured_s", optional(r.measured_s)}});
  }
  return j.dump(2) + "\n";
}

bool passed(const std::vector<Judge::Row>& rows)
{
  return std::all_of(rows.begin(), rows.end(), [](const Judge::Row& r) { return r.pass; });
}

std::string toTable(const std::string& scenario_name, const std::vector<Judge::Row>& rows)
{
  std::size_t w[6] = {4, 5, 11, 11, 5, 8};
  const auto widen = [&](std::size_t i, const std::string& s) { w[i] = std::max(w[i], s.size()); };
  for (const auto& r : rows) {
    widen(0, r.step);
    widen(1, r.fault);
    widen(2, r.expectation);
    widen(3, r.bound);
    widen(4, r.measured);
  }
  const auto line = [&](const std::string& a, const std::string& b, const std::string& c, const std::string& d,
                        const std::string& e, const std::string& f) {
    return fmt::format("{:<{}}  {:<{}}  {:<{}}  {:<{}}  {:<{}}  {}\n", a, w[0], b, w[1], c, w[2], d, w[3], e, w[4], f);
  };
  std::string out = line("STEP", "FAULT", "EXPECTATION", "BOUND", "MEASURED", "RESULT");
  for (const auto& r : rows) {
    out += line(r.step, r.fault, r.expectation, r.bound, r.measured, r.pass ? "PASS" : "FAIL");
  }
  const auto failures = std::count_if(rows.begin(), rows.end(), [](const Judge::Row& r) { return !r.pass; });
  out += failures == 0 ? fmt::format("scenario {}: PASS ({} checks)\n", scenario_name, rows.size())
                       : fmt::format("scenario {}: FAIL ({} of {} checks failed)\n", scenario_name, failures,
                                     rows.size());
  return out;
}

}  // namespace quad::fault
