// SPDX-License-Identifier: BSD-3-Clause
#include "quad/fault/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

#include "quad/common/params.hpp"
#include "quad/common/yaml_input.hpp"

namespace quad::fault {

namespace fs = std::filesystem;

namespace {

constexpr double kMaxTime = 1e6;  // [s] any time or bound beyond this is a typo
constexpr double kMaxListLength = 1e6;  // elements a stretched list may reach
constexpr double kMaxAltitude = 1e4;    // [m] an altitude_lost bound

const std::vector<std::pair<std::string, Action::Kind>> kProcessActions = {
    {"kill", Action::Kind::kKill},
    {"pause", Action::Kind::kPause},
    {"resume", Action::Kind::kResume},
    {"restart", Action::Kind::kRestart}};

const std::vector<std::pair<std::string, Expectation::Kind>> kExpectations = {
    {"mode", Expectation::Kind::kMode},
    {"noticed", Expectation::Kind::kNoticed},
    {"back", Expectation::Kind::kBack},
    {"rejected", Expectation::Kind::kRejected},
    {"altitude_lost", Expectation::Kind::kAltitudeLost},
    {"run_ended", Expectation::Kind::kRunEnded},
    {"outliers", Expectation::Kind::kOutliers}};
/// The sensors whose outliers the estimator counts (quad/estimation/state's *_rejected).
const std::vector<std::string> kGatedSensors = {"position", "baro", "mag"};

template <class Kind>
std::string nameOf(const std::vector<std::pair<std::string, Kind>>& table, Kind kind)
{
  for (const auto& [name, k] : table) {
    if (k == kind) {
      return name;
    }
  }
  return "?";
}

std::string joined(const std::vector<std::string>& names)
{
  std::string out;
  for (const auto& n : names) {
    out += (out.empty() ? "" : ", ") + n;
  }
  return out;
}

constexpr const char* kFaultNames = "kill, pause, resume, restart, plant, publish, dds, link, operator_link, mark";

constexpr wire::DatagramFaultKind kDatagramKinds[] = {
    wire::DatagramFaultKind::kLoss, wire::DatagramFaultKind::kDelay, wire::DatagramFaultKind::kDuplicate,
    wire::DatagramFaultKind::kReorder, wire::DatagramFaultKind::kCorrupt};

bool isName(const YAML::Node& node)
{
  return node.IsScalar() && !node.Scalar().empty();
}

class Parser {
public:
  Parser(const fs::path& file, const ScenarioLookup& lookup) : r_(file.string()), file_(file), lookup_(lookup) {}

  Scenario parse(YAML::Node root)
  {
    Scenario s;
    s.file = file_;
    s.name = file_.stem().string();
    if (!root.IsMap()) {
      r_.problem("(top level)", root, "expected a map with manifest, steps and outcome");
      r_.throwIfAny();
    }
    r_.onlyKeys(root, "",
                {"name", "description", "manifest", "world", "mode", "state", "geofence", "set", "end_at", "vehicle", "steps",
                 "outcome"});
    if (root["name"].IsDefined()) {
      if (isName(root["name"])) {
        s.name = root["name"].Scalar();
      } else {
        r_.problem("name", root["name"], "expected a name");
      }
    }
    if (root["description"].IsScalar()) {
      s.description = root["description"].Scalar();
    }
    if (const auto m = path(root["manifest"], "manifest", true)) {
      s.manifest = *m;
    }
    s.world = path(root["world"], "world", false);
    s.geofence = common::readGeofence(root["geofence"], "geofence", r_);
    // A key replacing the manifest's, one of two words.
    const auto either = [&](const char* key, const char* a, const char* b) -> std::optional<std::string> {
      if (!root[key].IsDefined()) {
        return std::nullopt;
      }
      const std::string value = root[key].IsScalar() ? root[key].Scalar() : "";
      if (value != a && value != b) {
        r_.problem(key, root[key], std::string("expected ") + a + " or " + b);
        return std::nullopt;
      }
      return value;
    };
    s.mode = either("mode", "realtime", "lockstep");
    s.state = either("state", "estimate", "truth");
    if (YAML::Node set = root["set"]; set.IsDefined()) {
      if (!set.IsMap()) {
        r_.problem("set", set, "expected a map of modules to their parameters, e.g. {plant: {wind.steady: '[0, 5, 0]'}}");
      } else {
        for (auto kv : set) {
          const std::string module = kv.first.Scalar();
          s.sets[module] = r_.scalars(kv.second, "set." + module);
        }
      }
    }
    if (root["end_at"].IsDefined()) {
      s.end_s = r_.number(root["end_at"], "end_at", std::nullopt, 0.0, kMaxTime);
    }
    if (root["vehicle"].IsDefined()) {
      s.vehicle = vehicleId(root["vehicle"], "vehicle");
    }
    YAML::Node steps = root["steps"];
    if (!steps.IsSequence() || steps.size() == 0) {
      r_.problem("steps", steps, "expected a list of steps, each with at: and a fault");
    } else if (steps.size() > kMaxSteps) {
      r_.problem("steps", steps, fmt::format("{} steps: at most {}", steps.size(), kMaxSteps));
    } else {
      for (std::size_t i = 0; i < steps.size(); ++i) {
        if (auto step = this->step(steps[i], "steps[" + std::to_string(i) + "]", static_cast<std::uint32_t>(i + 1))) {
          s.steps.push_back(std::move(*step));
        }
      }
    }
    s.outcome = outcome(root["outcome"]);
    const bool mission_given = root["outcome"].IsMap() && root["outcome"]["mission"].IsDefined();
    if (s.end_s && s.outcome.mission != Outcome::Mission::kAny && mission_given) {
      r_.problem("outcome.mission", root["outcome"]["mission"], "a run ended by end_at has no mission outcome: use any");
    } else if (s.end_s) {
      s.outcome.mission = Outcome::Mission::kAny;
    }
    for (std::size_t i = 1; i < s.steps.size(); ++i) {
      if (s.steps[i].at_s < s.steps[i - 1].at_s) {
        r_.problem("steps[" + std::to_string(i) + "].at", steps[i]["at"], "steps must be in time order");
      }
    }
    if (s.end_s && !s.steps.empty() && *s.end_s < s.steps.back().at_s) {
      r_.problem("end_at", root["end_at"], "earlier than the last step");
    }
    r_.throwIfAny();
    return s;
  }

private:
  std::optional<fs::path> path(YAML::Node node, const std::string& key, bool required)
  {
    if (!node.IsDefined()) {
      if (required) {
        r_.problem(key, node, "missing");
      }
      return std::nullopt;
    }
    if (!isName(node)) {
      r_.problem(key, node, "expected a file path");
      return std::nullopt;
    }
    const fs::path p = fs::absolute(file_.parent_path() / node.Scalar()).lexically_normal();
    if (!fs::is_regular_file(p)) {
      r_.problem(key, node, "no such file (" + p.string() + ")");
      return std::nullopt;
    }
    return p;
  }

  std::optional<Step> step(YAML::Node node, const std::string& key, std::uint32_t number)
  {
    if (!node.IsMap()) {
      r_.problem(key, node, "expected a map with at: and a fault");
      return std::nullopt;
    }
    Step st;
    const auto at = r_.number(node["at"], key + ".at", std::nullopt, 0.0, kMaxTime);
    std::vector<std::string> actions;
    for (const auto& entry : node) {
      const std::string k = entry.first.Scalar();
      if (k == "at" || k == "expect") {
        continue;
      }
      actions.push_back(k);
    }
    if (actions.size() != 1) {
      r_.problem(key, node,
                 actions.empty() ? "no fault: expected one of " + std::string(kFaultNames)
                                 : "one fault per step, found " + joined(actions));
      return std::nullopt;
    }
    const auto action = this->action(actions[0], node[actions[0]], key + "." + actions[0], number);
    bool ok = at && action;
    YAML::Node expect = node["expect"];
    if (expect.IsDefined() && !expect.IsSequence()) {
      r_.problem(key + ".expect", expect, "expected a list");
      ok = false;
    } else if (expect.IsDefined()) {
      for (std::size_t i = 0; i < expect.size(); ++i) {
        if (auto e = expectation(expect[i], key + ".expect[" + std::to_string(i) + "]")) {
          st.expect.push_back(*e);
        } else {
          ok = false;
        }
      }
    }
    if (!ok) {
      return std::nullopt;
    }
    st.at_s = *at;
    st.action = *action;
    return st;
  }

  std::optional<Action> action(const std::string& name, YAML::Node node, const std::string& key, std::uint32_t number)
  {
    Action a;
    const auto process = std::find_if(kProcessActions.begin(), kProcessActions.end(),
                                      [&](const auto& p) { return p.first == name; });
    if (process != kProcessActions.end()) {
      if (!isName(node)) {
        r_.problem(key, node, "expected the name of a module of the manifest");
        return std::nullopt;
      }
      a.kind = process->second;
      a.module = node.Scalar();
      return a;
    }
    if (name == "plant") {
      auto f = plant::parseFault(r_, node, key, {});
      if (!f) {
        return std::nullopt;
      }
      a.kind = Action::Kind::kPlant;
      a.module = "plant";
      a.plant = *f;
      a.plant.id = number;
      return a;
    }
    if (name == "publish") {
      return publish(node, key);
    }
    if (name == "dds") {
      return datagrams(node, key, number);
    }
    if (name == "link") {
      return link(node, key);
    }
    if (name == "operator_link") {
      return operatorLink(node, key);
    }
    if (name == "mark") {
      if (!isName(node)) {
        r_.problem(key, node, "expected what the scenario's set-up does, in words (mark injects nothing)");
        return std::nullopt;
      }
      a.kind = Action::Kind::kMark;
      a.note = node.Scalar();
      return a;
    }
    r_.problem(key, node, "unknown fault: expected one of " + std::string(kFaultNames));
    return std::nullopt;
  }

  /// dds: {module, from, loss, delay, duplicate, reorder, corrupt, seed, duration}
  std::optional<Action> datagrams(YAML::Node node, const std::string& key, std::uint32_t number)
  {
    if (!node.IsMap()) {
      r_.problem(key, node, "expected a map with module and at least one of " + joined(datagramKeys()));
      return std::nullopt;
    }
    std::set<std::string> allowed = {"module", "from", "seed", "duration"};
    for (const auto& k : datagramKeys()) {
      allowed.insert(k);
    }
    r_.onlyKeys(node, key + ".", allowed);
    Action a;
    a.kind = Action::Kind::kDds;
    bool ok = true;
    if (!isName(node["module"])) {
      r_.problem(key + ".module", node["module"], "expected the name of a module of the manifest");
      ok = false;
    } else {
      a.module = node["module"].Scalar();
    }
    std::string from;
    if (node["from"].IsDefined()) {
      if (!isName(node["from"])) {
        r_.problem(key + ".from", node["from"], "expected the name of the sending participant");
        ok = false;
      } else {
        from = node["from"].Scalar();
      }
    }
    const auto seed = r_.number(node["seed"], key + ".seed", 1.0, 0.0, 4294967295.0);
    if (node["duration"].IsDefined()) {
      a.duration_s = r_.number(node["duration"], key + ".duration", std::nullopt, 0.001, kMaxTime);
      ok = ok && a.duration_s;
    }
    std::uint32_t k = 0;
    for (const auto kind : kDatagramKinds) {
      ++k;
      const std::string name = wire::toString(kind);
      if (!node[name].IsDefined()) {
        continue;
      }
      const auto magnitude = r_.number(node[name], key + "." + name, std::nullopt, -kMaxTime, kMaxTime);
      if (!magnitude || !seed) {
        ok = false;
        continue;
      }
      wire::DatagramFault f{kDatagramIdBase * number + k, kind, *magnitude, from,
                           static_cast<std::uint64_t>(*seed)};
      if (const std::string why = f.invalidReason(); !why.empty()) {
        r_.problem(key + "." + name, node[name], why);
        ok = false;
        continue;
      }
      a.datagrams.push_back(f);
    }
    if (ok && a.datagrams.empty()) {
      r_.problem(key, node, "no datagram fault: expected at least one of " + joined(datagramKeys()));
      ok = false;
    }
    return ok ? std::optional<Action>(a) : std::nullopt;
  }

  /// operator_link: {lost: true, duration}
  std::optional<Action> operatorLink(YAML::Node node, const std::string& key)
  {
    if (!node.IsMap()) {
      r_.problem(key, node, "expected a map with lost: true and, to restore it, duration: SECONDS");
      return std::nullopt;
    }
    r_.onlyKeys(node, key + ".", {"lost", "duration"});
    Action a;
    a.kind = Action::Kind::kOperatorLink;
    bool ok = true;
    if (!flag(node["lost"], key + ".lost", false)) {
      r_.problem(key + ".lost", node["lost"], "expected true (the link is lost; duration restores it)");
      ok = false;
    }
    if (node["duration"].IsDefined()) {
      a.duration_s = r_.number(node["duration"], key + ".duration", std::nullopt, 0.001, kMaxTime);
      ok = ok && a.duration_s;
    }
    return ok ? std::optional<Action>(a) : std::nullopt;
  }

  /// link: {host, loss | partition | down, duration}
  std::optional<Action> link(YAML::Node node, const std::string& key)
  {
    const char* expected = "expected a map with host and one of loss: P, partition: HOST, down: true";
    if (!node.IsMap()) {
      r_.problem(key, node, expected);
      return std::nullopt;
    }
    r_.onlyKeys(node, key + ".", {"host", "loss", "partition", "down", "duration"});
    Action a;
    a.kind = Action::Kind::kLink;
    bool ok = true;
    if (!isName(node["host"])) {
      r_.problem(key + ".host", node["host"], "expected the name of a network-namespace host of the manifest");
      ok = false;
    } else {
      a.link.host = node["host"].Scalar();
    }
    if (node["duration"].IsDefined()) {
      a.duration_s = r_.number(node["duration"], key + ".duration", std::nullopt, 0.001, kMaxTime);
      ok = ok && a.duration_s;
    }
    const int kinds = (node["loss"].IsDefined() ? 1 : 0) + (node["partition"].IsDefined() ? 1 : 0) +
                      (node["down"].IsDefined() ? 1 : 0);
    if (kinds != 1) {
      r_.problem(key, node, std::string(kinds == 0 ? "no link fault: " : "one link fault per step: ") + expected);
      return std::nullopt;
    }
    if (node["loss"].IsDefined()) {
      a.link.kind = launch::LinkFault::Kind::kLoss;
      const auto p = r_.number(node["loss"], key + ".loss", std::nullopt, 0.0, 1.0);
      if (p && *p <= 0.0) {
        r_.problem(key + ".loss", node["loss"], "expected a probability in (0, 1]");
      }
      ok = ok && p && *p > 0.0;
      a.link.probability = p.value_or(0.0);
    } else if (node["partition"].IsDefined()) {
      a.link.kind = launch::LinkFault::Kind::kPartition;
      if (!isName(node["partition"])) {
        r_.problem(key + ".partition", node["partition"], "expected the name of another host of the manifest");
        ok = false;
      } else {
        a.link.peer = node["partition"].Scalar();
      }
    } else {
      a.link.kind = launch::LinkFault::Kind::kDown;
      if (!flag(node["down"], key + ".down", false)) {
        r_.problem(key + ".down", node["down"], "expected true (a link is up unless a step takes it down)");
        ok = false;
      }
    }
    if (ok && a.link.kind == launch::LinkFault::Kind::kPartition && a.link.peer == a.link.host) {
      r_.problem(key + ".partition", node["partition"], "a host cannot be cut off from itself");
      ok = false;
    }
    return ok ? std::optional<Action>(a) : std::nullopt;
  }

  static std::vector<std::string> datagramKeys()
  {
    std::vector<std::string> keys;
    for (const auto kind : kDatagramKinds) {
      keys.push_back(wire::toString(kind));
    }
    return keys;
  }

  std::optional<Action> publish(YAML::Node node, const std::string& key)
  {
    if (!node.IsMap()) {
      r_.problem(key, node, "expected a map with topic, values, count and rate");
      return std::nullopt;
    }
    r_.onlyKeys(node, key + ".", {"topic", "values", "count", "rate", "lengths"});
    Action a;
    a.kind = Action::Kind::kPublish;
    if (node["lengths"].IsDefined() && !node["lengths"].IsMap()) {
      r_.problem(key + ".lengths", node["lengths"], "expected a map of list fields to lengths");
    } else if (node["lengths"].IsDefined()) {
      for (const auto& entry : node["lengths"]) {
        const std::string field = entry.first.Scalar();
        const std::string k = key + ".lengths." + field;
        const auto n = r_.number(entry.second, k, std::nullopt, 1.0, kMaxListLength);
        const YAML::Node list = node["values"].IsMap() ? node["values"][field] : YAML::Node();
        if (!list.IsSequence() || list.size() == 0) {
          r_.problem(k, entry.second, "values." + field + " must be a list with at least one element to repeat");
        } else if (n) {
          a.lengths[field] = static_cast<std::size_t>(*n);
        }
      }
    }
    const auto count = r_.number(node["count"], key + ".count", 1.0, 1.0, 100000.0);
    const auto rate = r_.number(node["rate"], key + ".rate", 10.0, 0.01, 10000.0);
    if (!isName(node["topic"])) {
      r_.problem(key + ".topic", node["topic"], "expected a topic name");
      return std::nullopt;
    }
    a.topic = node["topic"].Scalar();
    if (!node["values"].IsMap()) {
      r_.problem(key + ".values", node["values"], "expected a map of the sample's fields");
      return std::nullopt;
    }
    YAML::Emitter out;
    out << YAML::Flow << node["values"];
    a.values = out.c_str();
    if (lookup_.check_sample) {
      if (const std::string why = lookup_.check_sample(a.topic, a.values); !why.empty()) {
        r_.problem(key + ".values", node["values"], why);
        return std::nullopt;
      }
    }
    if (!count || !rate) {
      return std::nullopt;
    }
    a.count = static_cast<int>(*count);
    a.rate_hz = *rate;
    return a;
  }

  std::optional<Expectation> expectation(YAML::Node node, const std::string& key)
  {
    if (!node.IsMap()) {
      r_.problem(key, node, "expected a map such as {mode: HOVER, within: 0.5}");
      return std::nullopt;
    }
    Expectation e;
    std::optional<std::string> kind;
    for (const auto& [name, k] : kExpectations) {
      if (node[name].IsDefined()) {
        if (kind) {
          r_.problem(key, node, "one expectation per entry, found " + *kind + " and " + name);
          return std::nullopt;
        }
        kind = name;
        e.kind = k;
      }
    }
    if (!kind) {
      r_.problem(key, node, "expected one of mode, noticed, back, rejected, altitude_lost, run_ended, outliers");
      return std::nullopt;
    }
    r_.onlyKeys(node, key + ".", {*kind, "within", "since"});
    YAML::Node value = node[*kind];
    const auto within = r_.number(node["within"], key + ".within", std::nullopt, 0.0, kMaxTime);
    if (e.kind == Expectation::Kind::kAltitudeLost) {
      const auto metres = r_.number(value, key + ".altitude_lost", std::nullopt, 0.0, kMaxAltitude);
      if (!metres || !within) {
        return std::nullopt;
      }
      if (node["since"].IsDefined()) {
        r_.problem(key + ".since", node["since"], "only a mode expectation is measured from elsewhere than the fault");
        return std::nullopt;
      }
      e.metres = *metres;
      e.within_s = *within;
      return e;
    }
    if (!isName(value)) {
      r_.problem(key + "." + *kind, value,
                 e.kind == Expectation::Kind::kMode       ? "expected a mode"
                 : e.kind == Expectation::Kind::kOutliers ? "expected a sensor"
                                                          : "expected a module");
      return std::nullopt;
    }
    if (e.kind == Expectation::Kind::kMode) {
      if (std::find(lookup_.modes.begin(), lookup_.modes.end(), value.Scalar()) == lookup_.modes.end()) {
        r_.problem(key + ".mode", value, "not a controller mode (" + joined(lookup_.modes) + ")");
        return std::nullopt;
      }
      e.mode = value.Scalar();
    } else if (e.kind == Expectation::Kind::kOutliers &&
               std::find(kGatedSensors.begin(), kGatedSensors.end(), value.Scalar()) == kGatedSensors.end()) {
      r_.problem(key + ".outliers", value, "not a sensor the estimator gates (" + joined(kGatedSensors) + ")");
      return std::nullopt;
    } else {
      e.module = value.Scalar();
    }
    if (const YAML::Node since = node["since"]; since.IsDefined()) {
      const std::string text = since.IsScalar() ? since.Scalar() : "";
      if (e.kind != Expectation::Kind::kMode) {
        r_.problem(key + ".since", since, "only a mode expectation is measured from elsewhere than the fault");
        return std::nullopt;
      }
      if (text == "last_path") {
        e.since = Expectation::Since::kLastPath;
      } else if (text != "fault") {
        r_.problem(key + ".since", since, "expected fault or last_path");
        return std::nullopt;
      }
    }
    if (!within) {
      return std::nullopt;
    }
    e.within_s = *within;
    return e;
  }

  Outcome outcome(YAML::Node node)
  {
    Outcome o;
    if (!node.IsDefined()) {
      return o;
    }
    if (!node.IsMap()) {
      r_.problem("outcome", node, "expected a map with mission, collisions, finite_actuators, recording_loss");
      return o;
    }
    r_.onlyKeys(node, "outcome.", {"mission", "vehicles", "collisions", "finite_actuators", "recording_loss"});
    if (node["mission"].IsDefined()) {
      o.mission = mission(node["mission"], "outcome.mission").value_or(o.mission);
    }
    if (YAML::Node vehicles = node["vehicles"]; vehicles.IsDefined()) {
      if (!vehicles.IsMap()) {
        r_.problem("outcome.vehicles", vehicles, "expected a map of vehicle ids to success, failure or any");
      } else {
        for (auto kv : vehicles) {
          const std::string key = "outcome.vehicles." + kv.first.Scalar();
          const auto id = vehicleId(kv.first, key);
          const auto m = mission(kv.second, key);
          if (id && m) {
            o.vehicles[*id] = *m;
          }
        }
      }
    }
    if (const auto c = r_.number(node["collisions"], "outcome.collisions", 0.0, 0.0, 1e6)) {
      o.max_collisions = static_cast<int>(*c);
    }
    o.finite_actuators = flag(node["finite_actuators"], "outcome.finite_actuators", true);
    if (node["recording_loss"].IsDefined()) {
      const std::string v = node["recording_loss"].IsScalar() ? node["recording_loss"].Scalar() : "";
      if (v == "0" || v == "any") {
        o.zero_loss = v == "0";
      } else {
        r_.problem("outcome.recording_loss", node["recording_loss"], "expected 0 or any");
      }
    }
    return o;
  }

  /// success, failure, crashed or any.
  std::optional<Outcome::Mission> mission(const YAML::Node& node, const std::string& key)
  {
    const std::string m = node.IsScalar() ? node.Scalar() : "";
    if (m == "success") {
      return Outcome::Mission::kSuccess;
    }
    if (m == "failure") {
      return Outcome::Mission::kFailure;
    }
    if (m == "crashed") {
      return Outcome::Mission::kCrashed;
    }
    if (m == "any") {
      return Outcome::Mission::kAny;
    }
    r_.problem(key, node, "expected success, failure, crashed or any");
    return std::nullopt;
  }

  /// A vehicle id: a whole number, as a fleet manifest's `id`.
  std::optional<std::uint32_t> vehicleId(const YAML::Node& node, const std::string& key)
  {
    const auto id = r_.number(node, key, std::nullopt, 0.0, 1'000'000.0);
    if (id && *id != std::floor(*id)) {
      r_.problem(key, node, "expected a vehicle id (a whole number)");
      return std::nullopt;
    }
    return id ? std::optional<std::uint32_t>(static_cast<std::uint32_t>(*id)) : std::nullopt;
  }

  bool flag(YAML::Node node, const std::string& key, bool fallback) { return r_.flag(node, key, fallback).value_or(fallback); }

  common::YamlReader r_;
  fs::path file_;
  const ScenarioLookup& lookup_;
};

}  // namespace

std::string Action::describe() const
{
  switch (kind) {
    case Kind::kKill:
    case Kind::kPause:
    case Kind::kResume:
    case Kind::kRestart:
      return nameOf(kProcessActions, kind) + " " + module;
    case Kind::kPlant:
      return "plant " + plant.describe();
    case Kind::kPublish: {
      std::string out = "publish " + std::to_string(count) + " on " + topic;
      for (const auto& [field, n] : lengths) {
        out += fmt::format(" ({} of {})", field, n);
      }
      return out;
    }
    case Kind::kDds: {
      const std::string& from = datagrams.front().from;
      std::string out = "dds " + module + " <- " + (from.empty() ? "every sender" : from) + ":";
      for (const auto& d : datagrams) {
        out += fmt::format("{} {} {:g}{}", &d == &datagrams.front() ? "" : ",", wire::toString(d.kind), d.magnitude,
                           d.kind == wire::DatagramFaultKind::kDelay ? " s" : "");
      }
      out += fmt::format(" (seed {})", datagrams.front().seed);
      return duration_s ? out + fmt::format(" for {:g} s", *duration_s) : out;
    }
    case Kind::kLink:
      return "link " + link.describe() + (duration_s ? fmt::format(" for {:g} s", *duration_s) : "");
    case Kind::kMark:
      return "mark: " + note;
    case Kind::kOperatorLink:
      return "operator link lost" + (duration_s ? fmt::format(" for {:g} s", *duration_s) : "");
  }
  return "?";
}

std::string Expectation::describe() const
{
  if (kind == Kind::kAltitudeLost) {
    return "altitude lost";
  }
  const std::string what = nameOf(kExpectations, kind) + " " + (kind == Kind::kMode ? mode : module);
  return since == Since::kLastPath ? what + " after the last path" : what;
}

Scenario parseScenario(std::string_view yaml_text, const fs::path& file, const ScenarioLookup& lookup)
{
  YAML::Node root = common::parseYaml(yaml_text, file.string());
  return Parser(fs::absolute(file).lexically_normal(), lookup).parse(root);
}

Scenario loadScenario(const fs::path& file, const ScenarioLookup& lookup)
{
  return parseScenario(common::readTextFile(file), file, lookup);
}

std::vector<std::string> checkAgainstVehicles(const Scenario& s, const std::vector<std::uint32_t>& vehicle_ids, bool fleet)
{
  std::vector<std::string> problems;
  const std::string manifest = s.manifest.filename().string();
  const auto check = [&](const std::string& key, std::uint32_t vehicle) {
    const auto id = static_cast<std::int64_t>(vehicle);
    if (!fleet) {
      problems.push_back(common::configProblem(s.file.string(), key, id, manifest + " flies one vehicle, not a fleet"));
    } else if (std::find(vehicle_ids.begin(), vehicle_ids.end(), vehicle) == vehicle_ids.end()) {
      problems.push_back(common::configProblem(s.file.string(), key, id,
                                               fmt::format("not a vehicle of {} ({})", manifest, fmt::join(vehicle_ids, ", "))));
    }
  };
  if (s.vehicle) {
    check("vehicle", *s.vehicle);
  }
  for (const auto& [id, mission] : s.outcome.vehicles) {
    check("outcome.vehicles." + std::to_string(id), id);
  }
  return problems;
}

std::vector<std::string> checkAgainstModules(const Scenario& s, const std::vector<std::string>& modules,
                                             const std::vector<std::string>& kinds,
                                             const std::map<std::string, bool>& hosts)
{
  std::vector<std::string> problems;
  const auto has = [&](const std::string& m) { return std::find(modules.begin(), modules.end(), m) != modules.end(); };
  const auto problem = [&](const std::string& key, const std::string& value, const std::string& why) {
    problems.push_back(common::configProblem(s.file.string(), key, value, why));
  };
  const std::string known = "not a module of " + s.manifest.filename().string() + " (" + joined(modules) + ")";
  for (const auto& [module, values] : s.sets) {
    if (!has(module)) {
      problem("set." + module, module, known);
    }
  }
  for (std::size_t i = 0; i < s.steps.size(); ++i) {
    const Step& st = s.steps[i];
    const std::string key = "steps[" + std::to_string(i) + "]";
    const Action& a = st.action;
    if (a.kind == Action::Kind::kPlant) {
      if (std::find(kinds.begin(), kinds.end(), "plant") == kinds.end()) {
        problem(key + ".plant", a.plant.describe(), s.manifest.filename().string() + " starts no plant to apply it");
      }
    } else if (a.kind == Action::Kind::kLink) {
      const auto host = hosts.find(a.link.host);
      if (host == hosts.end() || !host->second) {
        std::string netns;
        for (const auto& [name, is_netns] : hosts) {
          netns += is_netns ? (netns.empty() ? "" : ", ") + name : "";
        }
        problem(key + ".link.host", a.link.host,
                "not a network-namespace host of " + s.manifest.filename().string() +
                    (netns.empty() ? " (it has none: link faults need hosts of type netns)" : " (" + netns + ")"));
      }
      if (a.link.kind == launch::LinkFault::Kind::kPartition && hosts.count(a.link.peer) == 0) {
        problem(key + ".link.partition", a.link.peer, "not a host of " + s.manifest.filename().string());
      }
    } else if (a.kind == Action::Kind::kDds) {
      if (!has(a.module)) {
        problem(key + ".dds.module", a.module, known);
      }
      const std::string& from = a.datagrams.front().from;
      if (!from.empty() && std::find(kinds.begin(), kinds.end(), from) == kinds.end()) {
        problem(key + ".dds.from", from,
                "no module of " + s.manifest.filename().string() + " sends as '" + from +
                    "' (a module's participant is named after its kind: " + joined(kinds) + ")");
      }
    } else if (a.kind != Action::Kind::kPublish && a.kind != Action::Kind::kMark &&
               a.kind != Action::Kind::kOperatorLink && !has(a.module)) {
      problem(key + "." + nameOf(kProcessActions, a.kind), a.module, known);
    }
    for (std::size_t j = 0; j < st.expect.size(); ++j) {
      const Expectation& e = st.expect[j];
      const bool names_module = e.kind != Expectation::Kind::kMode && e.kind != Expectation::Kind::kAltitudeLost &&
                                e.kind != Expectation::Kind::kOutliers;
      if (names_module && !has(e.module)) {
        problem(key + ".expect[" + std::to_string(j) + "]." + nameOf(kExpectations, e.kind), e.module, known);
      }
    }
  }
  return problems;
}

std::vector<std::string> checkAgainstContainers(const Scenario& s, const launch::Manifest& manifest)
{
  std::vector<std::string> problems;
  const auto hostedIn = [&](const std::string& module) -> const launch::Module* {
    const launch::Module* process = manifest.processOf(module);
    return process != nullptr && !process->hosted.empty() ? process : nullptr;
  };
  for (std::size_t i = 0; i < s.steps.size(); ++i) {
    const Action& a = s.steps[i].action;
    const std::string key = "steps[" + std::to_string(i) + "]";
    const bool on_process = a.kind == Action::Kind::kDds ||
                            std::any_of(kProcessActions.begin(), kProcessActions.end(),
                                        [&](const auto& action) { return action.second == a.kind; });
    if (const launch::Module* container = on_process ? hostedIn(a.module) : nullptr) {
      std::vector<std::string> others;
      for (const auto& hosted : container->hosted) {
        if (hosted.name != a.module) {
          others.push_back(hosted.name);
        }
      }
      problems.push_back(common::configProblem(
          s.file.string(), key + (a.kind == Action::Kind::kDds ? ".dds.module" : "." + nameOf(kProcessActions, a.kind)),
          a.module,
          "shares process " + container->name + " with " + joined(others) +
              " in the composed layout: a fault on it alone needs the distributed layout"));
    }
  }
  return problems;
}

}  // namespace quad::fault
