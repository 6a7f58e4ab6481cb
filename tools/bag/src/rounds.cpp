// SPDX-License-Identifier: BSD-3-Clause
#include "quad/bag/rounds.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <set>

#include "quad/bag/audit.hpp"
#include "quad/common/payload_header.hpp"
#include "quad/introspection/cdr.hpp"
#include "quad/introspection/idl.hpp"

namespace quad::bag {

namespace {

// Where Header.publish_ns and Header.seq lie in a plain CDR payload: after the 4-byte
// encapsulation, vehicle_id (4 bytes, padded to 8) and stamp_ns.
constexpr std::size_t kPublicationBegin = 4 + 16;
constexpr std::size_t kPublicationEnd = kPublicationBegin + 16;

/// The same sample sent again: equal but for its publication time and number.
bool resent(const Message& a, const Message& b)
{
  if (a.data.size() != b.data.size() || a.data.size() < kPublicationEnd) {
    return false;
  }
  return std::equal(a.data.begin(), a.data.begin() + kPublicationBegin, b.data.begin()) &&
         std::equal(a.data.begin() + kPublicationEnd, a.data.end(), b.data.begin() + kPublicationEnd);
}

}  // namespace

std::vector<Round> lockstepRounds(const McapContents& c, const std::string& clock_topic,
                                  const std::function<bool(const std::string& topic)>& is_input)
{
  std::map<std::uint16_t, bool> clock_channel;  // channel id -> true for the clock, false for an input
  for (const auto& ch : c.channels) {
    if (ch.topic == clock_topic) {
      clock_channel[ch.id] = true;
    } else if (is_input(ch.topic)) {
      clock_channel[ch.id] = false;
    }
  }
  const auto& schema = introspection::quadSchema();
  std::map<std::int64_t, Round> rounds;
  struct Input {
    std::int64_t stamp_ns;
    const Message* message;
  };
  std::vector<Input> inputs;
  for (const auto& m : c.messages) {
    const auto it = clock_channel.find(m.channel_id);
    if (it == clock_channel.end()) {
      continue;
    }
    if (it->second) {
      nlohmann::ordered_json clock;
      try {
        clock = introspection::decodeCdr(schema, "quad::msg::SimClock", m.data);
      } catch (const introspection::DecodeError& e) {
        throw BagError(clock_topic + ": a sample does not decode as quad::msg::SimClock: " + e.what());
      }
      const auto sim_ns = clock["sim_ns"].get<std::int64_t>();
      if (!rounds.contains(sim_ns)) {
        rounds[sim_ns] = Round{&m, sim_ns, clock["state_sent"].get<bool>(), {}};
      }
      continue;
    }
    if (const auto header = common::payloadHeader(m.data)) {
      inputs.push_back({header->stamp_ns, &m});
    }
  }
  std::stable_sort(inputs.begin(), inputs.end(), [](const Input& a, const Input& b) { return a.stamp_ns < b.stamp_ns; });
  std::map<std::uint16_t, const Message*> last;  // per channel: the newest input kept
  for (const Input& in : inputs) {
    const auto round = rounds.lower_bound(in.stamp_ns);
    if (round == rounds.end()) {
      continue;
    }
    const Message*& previous = last[in.message->channel_id];
    if (previous != nullptr && resent(*previous, *in.message)) {
      continue;
    }
    previous = in.message;
    round->second.inputs.push_back(in.message);
  }
  std::vector<Round> out;
  out.reserve(rounds.size());
  for (auto& [t, r] : rounds) {
    out.push_back(std::move(r));
  }
  return out;
}

std::optional<LostInput> firstLostInput(const McapContents& c, const std::function<bool(const std::string& topic)>& is_input)
{
  const auto loss = metadataValues(c, kLossMetadata);
  std::map<std::uint16_t, std::string> lossy;  // channel id -> topic
  std::map<std::string, bool> one_writer;
  for (const auto& ch : c.channels) {
    const auto it = loss.find(ch.topic);
    const auto figures = it == loss.end() ? std::nullopt : parseLossFigures(it->second);
    if (is_input(ch.topic) && figures && figures->missing > 0) {
      lossy[ch.id] = ch.topic;
      one_writer[ch.topic] = parseLossWriters(it->second).value_or(0) == 1;
    }
  }
  std::optional<LostInput> first;
  std::map<std::uint16_t, std::pair<std::uint64_t, std::int64_t>> previous;  // channel -> (seq, stamp)
  std::set<std::uint16_t> placed;
  for (const auto& m : c.messages) {
    const auto it = lossy.find(m.channel_id);
    const auto header = it == lossy.end() || placed.contains(m.channel_id) ? std::nullopt : common::payloadHeader(m.data);
    if (!header) {
      continue;
    }
    const auto prev = previous.find(m.channel_id);
    std::optional<std::int64_t> last_whole;
    if (!one_writer[it->second]) {
      last_whole = header->stamp_ns;
    } else if (prev != previous.end() && header->seq > prev->second.first + 1) {
      last_whole = prev->second.second;
    }
    if (last_whole) {
      placed.insert(m.channel_id);
      if (!first || *last_whole < first->last_whole_ns) {
        first = LostInput{it->second, *last_whole};
      }
      continue;
    }
    previous[m.channel_id] = {header->seq, header->stamp_ns};
  }
  return first;
}

}  // namespace quad::bag
