// SPDX-License-Identifier: BSD-3-Clause
#include "quad/bag/compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "quad/bag/audit.hpp"
#include "quad/introspection/cdr.hpp"

namespace quad::bag {

namespace {

namespace in = quad::introspection;
using Json = nlohmann::ordered_json;

struct TopicMessages {
  std::string type;  // scoped ("quad::msg::Path")
  std::vector<const Message*> messages;
  double rate_hz = 0.0;  // its contract's, as the recorder noted it on the channel; 0: unknown or none
};

std::map<std::string, TopicMessages> byTopic(const McapContents& c, const CompareOptions& options)
{
  std::map<std::uint16_t, std::string> schema_names;
  for (const auto& s : c.schemas) {
    schema_names[s.id] = s.name;
  }
  std::map<std::uint16_t, TopicMessages*> channels;
  std::map<std::string, TopicMessages> topics;
  for (const auto& ch : c.channels) {
    if (options.selected && !options.selected(ch.topic)) {
      continue;
    }
    TopicMessages& t = topics[ch.topic];
    t.type = schema_names[ch.schema_id];  // the DDS type name, which is the IDL's scoped name
    if (const auto rate = ch.metadata.find("rate_hz"); rate != ch.metadata.end()) {
      try {
        t.rate_hz = std::stod(rate->second);
      } catch (const std::exception&) {
        t.rate_hz = 0.0;
      }
    }
    channels[ch.id] = &t;
  }
  for (const auto& m : c.messages) {
    if (const auto it = channels.find(m.channel_id); it != channels.end()) {
      it->second->messages.push_back(&m);
    }
  }
  return topics;
}

/// Walks two decoded values of one IDL type side by side.
class Walker {
public:
  Walker(const in::Schema& schema, const std::set<std::string>& ignored) : schema_(schema), ignored_(ignored) {}

  /// The first member that differs: its path and both values; nothing when they agree.
  std::optional<Difference> structs(const Json& a, const Json& b, const in::StructDef& def, const std::string& path)
  {
    for (const auto& m : def.members) {
      if (ignored_.count(def.name + "." + m.name) != 0) {
        continue;
      }
      const std::string at = path.empty() ? m.name : path + "." + m.name;
      const Json& x = a.contains(m.name) ? a.at(m.name) : kNull;
      const Json& y = b.contains(m.name) ? b.at(m.name) : kNull;
      if (auto d = m.array_dims.empty() ? value(x, y, m.type, at) : elements(x, y, m.type, at)) {
        return d;
      }
    }
    return std::nullopt;
  }

private:
  std::optional<Difference> value(const Json& a, const Json& b, const in::TypeRef& type, const std::string& path)
  {
    if (type.kind == in::TypeRef::Kind::kSequence && type.element) {
      return elements(a, b, *type.element, path);
    }
    if (type.kind == in::TypeRef::Kind::kNamed) {
      if (const in::StructDef* def = schema_.findStruct(type.name); def && a.is_object() && b.is_object()) {
        return structs(a, b, *def, path);
      }
    }
    return leaf(a, b, path);
  }

  std::optional<Difference> elements(const Json& a, const Json& b, const in::TypeRef& element, const std::string& path)
  {
    if (!a.is_array() || !b.is_array()) {
      return leaf(a, b, path);
    }
    const std::size_t n = std::min(a.size(), b.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (auto d = value(a[i], b[i], element, path + "[" + std::to_string(i) + "]")) {
        return d;
      }
    }
    if (a.size() != b.size()) {
      return Difference{{}, 0, 0, path + " length", std::to_string(a.size()), std::to_string(b.size())};
    }
    return std::nullopt;
  }

  static std::optional<Difference> leaf(const Json& a, const Json& b, const std::string& path)
  {
    if (a.is_number_float() && b.is_number_float() && std::isnan(a.get<double>()) && std::isnan(b.get<double>())) {
      return std::nullopt;
    }
    if (a == b) {
      return std::nullopt;
    }
    return Difference{{}, 0, 0, path, a.dump(), b.dump()};
  }

  static inline const Json kNull = nullptr;
  const in::Schema& schema_;
  const std::set<std::string>& ignored_;
};

/// A topic's messages decoded, in the order their writers stamped and numbered them.
struct Decoded {
  struct Entry {
    std::int64_t stamp_ns = 0;
    std::uint32_t vehicle = 0;  // Header.vehicle_id: a fleet's samples of one stamp, vehicle by vehicle
    std::uint64_t seq = 0;  // its place among the topic's messages of that stamp
    const Message* message = nullptr;
    Json value;  // null when the payload is not its type
  };
  std::vector<Entry> entries;
  bool headers = false;  // every message has quad's Header: aligned by (stamp, seq)
};

Decoded decode(const in::Schema& schema, const in::StructDef* def, const std::vector<const Message*>& messages,
               const std::set<std::string>& ignored)
{
  Decoded d;
  d.headers = def != nullptr && !def->members.empty() && def->members.front().name == "header";
  for (const Message* m : messages) {
    Decoded::Entry e{0, 0, 0, m, nullptr};
    if (def != nullptr) {
      try {
        e.value = in::decodeCdr(schema, def->name, m->data);
        if (d.headers) {
          e.stamp_ns = e.value["header"]["stamp_ns"].get<std::int64_t>();
          e.vehicle = e.value["header"]["vehicle_id"].get<std::uint32_t>();
        }
      } catch (const in::DecodeError&) {
        d.headers = false;
      }
    }
    d.entries.push_back(std::move(e));
  }
  if (!d.headers) {
    return d;
  }
  // Of one stamp, a fleet's vehicles' samples come in whatever order their writers' turns
  // fell: vehicle by vehicle, each in its recorded order.
  std::stable_sort(d.entries.begin(), d.entries.end(), [](const Decoded::Entry& l, const Decoded::Entry& r) {
    return std::pair(l.stamp_ns, l.vehicle) < std::pair(r.stamp_ns, r.vehicle);
  });
  // A sample sent again (a waiting lockstep plant resends its clock, state and cloud until
  // they are taken) differs from the first only in its number and publication time: once.
  std::set<std::string> resend = ignored;
  resend.insert("quad::msg::Header.seq");
  Walker same(schema, resend);
  std::vector<Decoded::Entry> kept;
  for (auto& e : d.entries) {
    if (!kept.empty() && kept.back().stamp_ns == e.stamp_ns && !same.structs(kept.back().value, e.value, *def, "")) {
      continue;
    }
    e.seq = !kept.empty() && kept.back().stamp_ns == e.stamp_ns ? kept.back().seq + 1 : 0;
    kept.push_back(std::move(e));
  }
  d.entries = std::move(kept);
  return d;
}

std::uint64_t recordedLoss(const McapContents& c, const std::string& topic)
{
  const auto loss = metadataValues(c, kLossMetadata);
  const auto it = loss.find(topic);
  const auto f = it == loss.end() ? std::nullopt : parseLossFigures(it->second);
  return f ? f->missing : 0;
}

/// The newest sim time a recording's clock reached (its end), if it has a clock.
std::optional<std::int64_t> clockEnd(const std::map<std::string, TopicMessages>& topics, const std::string& clock,
                                     const in::Schema& schema)
{
  const auto it = topics.find(clock);
  if (it == topics.end() || it->second.messages.empty()) {
    return std::nullopt;
  }
  std::int64_t end = 0;
  for (const Message* m : it->second.messages) {
    try {
      end = std::max(end, in::decodeCdr(schema, it->second.type, m->data)["header"]["stamp_ns"].get<std::int64_t>());
    } catch (const in::DecodeError&) {
    }
  }
  return end;
}

}  // namespace

Comparison compareRecordings(const McapContents& a, const McapContents& b, const CompareOptions& options)
{
  const in::Schema& schema = in::quadSchema();
  const std::set<std::string> ignored(options.ignored_fields.begin(), options.ignored_fields.end());
  CompareOptions with_clock = options;
  with_clock.selected = nullptr;
  const auto first = byTopic(a, options);
  const auto second = byTopic(b, options);
  // Either recording may stop before the other: compare up to the sooner end, that instant
  // left out (a plant stopped there reports the run's end with its stamp).
  const auto end_a = clockEnd(byTopic(a, with_clock), options.clock_topic, schema);
  const auto end_b = clockEnd(byTopic(b, with_clock), options.clock_topic, schema);
  const std::int64_t end = end_a && end_b ? std::min(*end_a, *end_b) : std::numeric_limits<std::int64_t>::max();
  Comparison result;
  struct Found {
    std::uint64_t log_time;
    Difference d;
  };
  std::vector<Found> found;
  std::set<std::string> names;
  for (const auto& [t, m] : first) {
    names.insert(t);
  }
  for (const auto& [t, m] : second) {
    names.insert(t);
  }
  for (const std::string& topic : names) {
    const auto x = first.find(topic);
    const auto y = second.find(topic);
    if (x == first.end() || y == second.end()) {
      found.push_back({0, {topic, 0, 0, "topic", x == first.end() ? "absent" : "present",
                           y == second.end() ? "absent" : "present"}});
      continue;
    }
    ++result.topics;
    const in::StructDef* def = schema.findStruct(x->second.type);
    const Decoded da = decode(schema, def, x->second.messages, ignored);
    const Decoded db = decode(schema, def, y->second.messages, ignored);
    const bool aligned = da.headers && db.headers;
    // Aligned by stamp (and place among that stamp's), from where both recorded the topic (a recorder
    // subscribes once it sees a writer) to the sooner end.
    std::int64_t from = 0;
    if (aligned && !da.entries.empty() && !db.entries.empty()) {
      from = std::max(da.entries.front().stamp_ns, db.entries.front().stamp_ns);
    }
    const auto inside = [&](const Decoded::Entry& e) {
      return !aligned || (e.stamp_ns >= from && e.stamp_ns < end);
    };
    std::vector<const Decoded::Entry*> ea, eb;
    for (const auto& e : da.entries) {
      if (inside(e)) {
        ea.push_back(&e);
      }
    }
    for (const auto& e : db.entries) {
      if (inside(e)) {
        eb.push_back(&e);
      }
    }
    const std::uint64_t lost_a = recordedLoss(a, topic);
    const std::uint64_t lost_b = recordedLoss(b, topic);
    // A sample lost in the last period of its topic before the end leaves no later number to
    // reveal the loss: there, one only one recording holds is passed over.
    const double rate = std::max(x->second.rate_hz, y->second.rate_hz);
    const std::int64_t tail_from = aligned && rate > 0.0 && end != std::numeric_limits<std::int64_t>::max()
                                       ? end - static_cast<std::int64_t>(1e9 / rate)
                                       : std::numeric_limits<std::int64_t>::max();
    std::uint64_t only_a = 0, only_b = 0;
    Walker walker(schema, ignored);
    std::optional<Found> at;
    std::size_t i = 0, j = 0;
    for (std::uint64_t index = 1; (i < ea.size() || j < eb.size()) && !at; ++index) {
      const Decoded::Entry* p = i < ea.size() ? ea[i] : nullptr;
      const Decoded::Entry* q = j < eb.size() ? eb[j] : nullptr;
      const auto key = [](const Decoded::Entry* e) { return std::pair(e->stamp_ns, e->seq); };
      if (aligned && p && q && key(p) != key(q)) {
        // A message only one recording holds: the other's recorder lost it, as its loss
        // figures say, or the runs differ here.
        const bool a_first = key(p) < key(q);
        if ((a_first ? p : q)->stamp_ns >= tail_from || (a_first ? ++only_a <= lost_b : ++only_b <= lost_a)) {
          a_first ? ++i : ++j;
          continue;
        }
      }
      if (!p || !q || (aligned && key(p) != key(q))) {
        const Decoded::Entry* e = p ? p : q;
        if ((!p || !q) && e->stamp_ns >= tail_from) {
          p ? ++i : ++j;
          continue;
        }
        at = Found{e->message->log_time,
                   {topic, index, e->stamp_ns, "message", p && (!q || key(p) < key(q)) ? "present" : "absent",
                    q && (!p || key(q) < key(p)) ? "present" : "absent"}};
        break;
      }
      std::optional<Difference> d;
      if (!p->value.is_null() && !q->value.is_null()) {
        d = walker.structs(p->value, q->value, *def, "");
      } else if (p->message->data != q->message->data) {
        d = Difference{{}, 0, 0, "payload", std::to_string(p->message->data.size()) + " bytes",
                       std::to_string(q->message->data.size()) + " bytes"};
      }
      if (d) {
        d->topic = topic;
        d->index = index;
        d->stamp_ns = p->stamp_ns;
        at = Found{p->message->log_time, *d};
      } else {
        ++result.messages;
      }
      ++i;
      ++j;
    }
    if (at) {
      found.push_back(*at);
    }
  }
  std::stable_sort(found.begin(), found.end(), [](const Found& l, const Found& r) { return l.log_time < r.log_time; });
  for (auto& f : found) {
    result.differences.push_back(std::move(f.d));
  }
  return result;
}

}  // namespace quad::bag
