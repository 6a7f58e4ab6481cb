// SPDX-License-Identifier: BSD-3-Clause
#include "quad/report/flight.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <span>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "quad/bag/audit.hpp"
#include "quad/introspection/cdr.hpp"
#include "quad/introspection/idl.hpp"
#include "quad/mapping/mapper.hpp"

namespace quad::report {

namespace {

using Json = nlohmann::ordered_json;

constexpr double kKeepPeriodS = 0.04;  // trajectories: a sample per 40 ms of sim time

/// A recorded channel and the schema its messages decode with.
struct Decoder {
  std::string topic;
  std::string type;
  introspection::Schema schema;
  std::optional<double> contract_hz;

  Json decode(const bag::Message& m, std::string_view type_name) const
  {
    try {
      return introspection::decodeCdr(schema, type_name, std::span<const std::uint8_t>(m.data));
    } catch (const std::exception& e) {
      throw FlightError(fmt::format("{}: a {} message does not decode: {}", topic, type_name, e.what()));
    }
  }
  Json decode(const bag::Message& m) const { return decode(m, type); }
};

/// A member of a decoded message, or a FlightError naming the topic and the member.
const Json& field(const Json& message, const char* name, const std::string& topic)
{
  const auto it = message.find(name);
  if (it == message.end()) {
    throw FlightError(fmt::format("{}: the recorded messages have no member '{}'", topic, name));
  }
  return *it;
}

Vector3 vector(const Json& v, const std::string& topic)
{
  return {field(v, "x", topic).get<double>(), field(v, "y", topic).get<double>(), field(v, "z", topic).get<double>()};
}

geometry::Quaternion quaternion(const Json& q, const std::string& topic)
{
  return {field(q, "w", topic).get<double>(), field(q, "x", topic).get<double>(), field(q, "y", topic).get<double>(),
          field(q, "z", topic).get<double>()};
}

double stampOf(const Json& message, const std::string& topic)
{
  return static_cast<double>(field(field(message, "header", topic), "stamp_ns", topic).get<std::int64_t>()) * 1e-9;
}

std::map<std::uint16_t, Decoder> decoders(const bag::McapContents& recording)
{
  std::map<std::uint16_t, const bag::Schema*> schemas;
  for (const auto& s : recording.schemas) {
    schemas[s.id] = &s;
  }
  std::map<std::uint16_t, Decoder> out;
  for (const auto& ch : recording.channels) {
    const auto s = schemas.find(ch.schema_id);
    if (s == schemas.end() || s->second->encoding != "omgidl" || ch.message_encoding != "cdr" ||
        !s->second->name.starts_with("quad::msg::")) {
      continue;  // not a quad message (a display topic's Foxglove schema): nothing the report reads
    }
    Decoder d;
    d.topic = ch.topic;
    d.type = s->second->name;
    try {
      d.schema.addFile(d.type, s->second->data);
      d.schema.link();
    } catch (const std::exception& e) {
      throw FlightError(fmt::format("{}: its schema {} does not parse: {}", ch.topic, d.type, e.what()));
    }
    if (const auto rate = ch.metadata.find("rate_hz"); rate != ch.metadata.end()) {
      try {
        const double hz = std::stod(rate->second);
        if (hz > 0.0 && std::isfinite(hz)) {
          d.contract_hz = hz;
        }
      } catch (const std::exception&) {
        // a channel without a readable rate is drawn without its contract
      }
    }
    out.emplace(ch.id, std::move(d));
  }
  return out;
}

/// Appends `s` when it is kKeepPeriodS past the last kept sample.
void keep(std::vector<FlightData::State>& series, const FlightData::State& s)
{
  if (series.empty() || s.t_s >= series.back().t_s + kKeepPeriodS || s.t_s < series.back().t_s) {
    series.push_back(s);
  }
}

}  // namespace

FlightData readFlight(const bag::McapContents& recording, const Progress& progress, std::optional<std::uint32_t> vehicle)
{
  const std::map<std::uint16_t, Decoder> channels = decoders(recording);
  FlightData f;
  f.messages = recording.messages.size();
  launch::EstimateScore score;
  struct Span {
    std::uint64_t n = 0;
    std::uint64_t at_first = 0;  // samples stamped with the first stamp (sim time held before the start)
    double first = 0.0;
    double last = 0.0;
  };
  std::map<std::uint16_t, Span> spans;
  const bag::Message* last_snapshot = nullptr;
  bool any_state = false;
  std::set<std::uint32_t> vehicles_seen;  // in the vehicle states
  const std::size_t total = recording.messages.size();
  for (std::size_t k = 0; k < total; ++k) {
    if (progress && k % 20000 == 0) {
      progress(k, total);
    }
    const bag::Message& m = recording.messages[k];
    const auto ch = channels.find(m.channel_id);
    if (ch == channels.end()) {
      continue;
    }
    const Decoder& d = ch->second;
    const std::string& topic = d.topic;
    // The topics drawn are decoded whole; of the others, every quad message starts with its
    // Header: the rate of each topic from its stamps.
    static const std::set<std::string, std::less<>> kDrawn{"quad/sim/state",       "quad/estimation/state",
                                                            "quad/planning/goal",   "quad/planning/path",
                                                            "quad/control/status",  "quad/sim/events",
                                                            "quad/system/fault_events"};
    const Json msg = kDrawn.contains(topic) ? d.decode(m) : Json{{"header", d.decode(m, "quad::msg::Header")}};
    const auto vehicle_id = field(field(msg, "header", topic), "vehicle_id", topic).get<std::uint32_t>();
    if (topic == "quad/sim/state") {
      vehicles_seen.insert(vehicle_id);
    }
    if (vehicle && vehicle_id != *vehicle && topic != "quad/system/fault_events") {
      continue;
    }
    const double header_t = stampOf(msg, topic);
    Span& span = spans[m.channel_id];
    if (span.n == 0 || header_t < span.first) {
      span.first = header_t;
      span.at_first = 0;
    }
    span.at_first += header_t == span.first ? 1 : 0;
    span.last = span.n == 0 ? header_t : std::max(span.last, header_t);
    ++span.n;

    if (topic == "quad/sim/state") {
      const double t = header_t;
      const Vector3 p = vector(field(msg, "p_W", topic), topic);
      const Vector3 v = vector(field(msg, "v_W", topic), topic);
      score.onTruth(static_cast<std::int64_t>(std::llround(t * 1e9)), p, quaternion(field(msg, "q_WB", topic), topic), v);
      keep(f.truth, {t, p, v});
      if (!any_state) {
        f.t_first_s = t;
      }
      f.t_first_s = std::min(f.t_first_s, t);
      f.t_last_s = std::max(f.t_last_s, t);
      any_state = true;
    } else if (topic == "quad/estimation/state") {
      const double t = header_t;
      const bool aligned = field(msg, "aligned", topic).get<bool>();
      const Vector3 p = vector(field(msg, "p_W", topic), topic);
      score.onEstimate(static_cast<std::int64_t>(std::llround(t * 1e9)), p, quaternion(field(msg, "q_WB", topic), topic),
                       vector(field(msg, "p_std", topic), topic), aligned);
      if (aligned) {
        keep(f.estimate, {t, p, vector(field(msg, "v_W", topic), topic)});
      }
    } else if (topic == "quad/planning/goal") {
      f.goals.push_back({header_t, vector(field(msg, "p_W", topic), topic), field(msg, "tolerance", topic).get<double>()});
    } else if (topic == "quad/planning/path") {
      FlightData::Path p;
      p.t_s = header_t;
      p.version = field(msg, "version", topic).get<std::uint32_t>();
      p.status = field(msg, "status", topic).get<std::string>();
      for (const Json& w : field(msg, "waypoints_W", topic)) {
        p.waypoints_W.push_back(vector(w, topic));
      }
      p.expansions = field(msg, "expansions", topic).get<std::uint64_t>();
      p.replan_time_s = field(msg, "replan_time_s", topic).get<double>();
      f.paths.push_back(std::move(p));
    } else if (topic == "quad/control/status") {
      f.status.push_back({header_t, field(msg, "mode", topic).get<std::string>(),
                          field(msg, "failsafe_reason", topic).get<std::string>(),
                          vector(field(msg, "position_error_W", topic), topic).norm(),
                          field(msg, "attitude_error", topic).get<double>() * 180.0 / std::numbers::pi});
    } else if (topic == "quad/sim/events" || topic == "quad/system/fault_events") {
      f.events.push_back({header_t, field(msg, "kind", topic).get<std::string>(),
                          field(msg, "detail", topic).get<std::string>(), topic == "quad/system/fault_events"});
    } else if (topic == "quad/mapping/octomap") {
      last_snapshot = &m;
    }
  }
  if (progress) {
    progress(total, total);
  }
  if (!vehicle && vehicles_seen.size() > 1) {
    throw FlightError(fmt::format("quad/sim/state: the recording holds vehicles {}: choose one (quad report --vehicle N)",
                                  fmt::join(vehicles_seen, ", ")));
  }
  if (!any_state) {
    throw FlightError(vehicle ? fmt::format("quad/sim/state: the recording holds no state of vehicle {} (it holds {})",
                                            *vehicle, vehicles_seen.empty() ? "none" : fmt::format("{}", fmt::join(vehicles_seen, ", ")))
                              : "quad/sim/state: the recording holds no vehicle state (was the plant recorded?)");
  }
  if (last_snapshot != nullptr) {
    const Decoder& d = channels.at(last_snapshot->channel_id);
    const Json msg = d.decode(*last_snapshot);
    const double resolution = field(msg, "resolution", d.topic).get<double>();
    const std::vector<std::uint8_t> bytes = field(msg, "octree", d.topic).get<std::vector<std::uint8_t>>();
    auto centres = mapping::occupiedCentres(bytes, resolution);
    if (!centres) {
      throw FlightError(fmt::format("{}: the last snapshot is no OctoMap tree of resolution {} m", d.topic, resolution));
    }
    f.occupied_W = std::move(*centres);
    f.map_resolution_m = resolution;
  }
  // A contract's rate is each writer's (every module sends its heartbeat): the recorder's loss
  // figures count the writers.
  const auto loss = bag::metadataValues(recording, bag::kLossMetadata);
  for (const auto& [id, span] : spans) {
    const Decoder& d = channels.at(id);
    FlightData::TopicRate r{d.topic, span.n, 0.0, d.contract_hz, 1};
    if (const auto l = loss.find(d.topic); l != loss.end()) {
      r.writers = std::max(1, static_cast<int>(bag::parseLossWriters(l->second).value_or(1)));
    }
    if (span.n > span.at_first && span.last > span.first) {
      // Samples after the first stamp, over the time after it: a clock held at its start
      // (lockstep waiting for every module) adds samples but no time.
      r.rate_hz = static_cast<double>(span.n - span.at_first) / (span.last - span.first) / r.writers;
    }
    f.rates.push_back(r);
  }
  std::sort(f.events.begin(), f.events.end(), [](const auto& a, const auto& b) { return a.t_s < b.t_s; });
  f.estimate_error = score.series();
  return f;
}

}  // namespace quad::report
