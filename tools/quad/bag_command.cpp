// SPDX-License-Identifier: BSD-3-Clause
#include <algorithm>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bag_commands.hpp"
#include "quad/bag/audit.hpp"
#include "quad/bag/compare.hpp"
#include "quad/bag/mcap.hpp"
#include "quad/dds/topics.hpp"
#include "quad/introspection/cdr.hpp"
#include "quad/introspection/idl.hpp"
#include "quad/topic/connection.hpp"
#include "quad/topic/text_format.hpp"

namespace quad::tools {

int bagInfo(const std::string& file, bool json)
{
  bag::McapContents c;
  try {
    c = bag::readMcap(file, true);
  } catch (const bag::BagError& e) {
    std::fprintf(stderr, "bag info: %s\n", e.what());
    return 1;
  }
  std::map<std::uint16_t, const bag::Channel*> channels;
  for (const auto& ch : c.channels) {
    channels[ch.id] = &ch;
  }
  std::map<std::uint16_t, const bag::Schema*> schemas;
  for (const auto& s : c.schemas) {
    schemas[s.id] = &s;
  }
  struct Row {
    std::uint64_t count = 0;
    std::uint64_t first = 0, last = 0;
  };
  std::map<std::uint16_t, Row> rows;
  std::uint64_t first = 0, last = 0;
  for (const auto& m : c.messages) {
    Row& r = rows[m.channel_id];
    r.first = r.count == 0 ? m.log_time : std::min(r.first, m.log_time);
    r.last = std::max(r.last, m.log_time);
    ++r.count;
    first = first == 0 ? m.log_time : std::min(first, m.log_time);
    last = std::max(last, m.log_time);
  }
  const auto loss = bag::metadataValues(c, bag::kLossMetadata);
  const double span = static_cast<double>(last - first) * 1e-9;
  struct Topic {
    std::string topic, type;
    std::uint64_t messages = 0;
    std::optional<double> rate_hz;
    std::optional<std::string> loss;  // the recorder's figures
  };
  std::vector<Topic> topics;
  for (const auto& [id, ch] : channels) {
    const Row r = rows[id];
    const double s = static_cast<double>(r.last - r.first) * 1e-9;
    const auto schema_it = schemas.find(ch->schema_id);
    const auto l = loss.find(ch->topic);
    topics.push_back({ch->topic, schema_it == schemas.end() ? "?" : schema_it->second->name, r.count,
                      r.count > 1 && s > 0 ? std::optional(static_cast<double>(r.count - 1) / s) : std::nullopt,
                      l == loss.end() ? std::nullopt : std::optional(l->second)});
  }
  if (json) {
    nlohmann::ordered_json j;
    j["file"] = file;
    j["complete"] = c.complete;
    j["problem"] = c.problem;
    j["messages"] = c.messages.size();
    j["chunks"] = c.chunks;
    j["duration_s"] = span;
    j["topics"] = nlohmann::ordered_json::array();
    for (const Topic& t : topics) {
      nlohmann::ordered_json figures = nullptr;
      if (const auto f = t.loss ? bag::parseLossFigures(*t.loss) : std::nullopt) {
        figures = {{"received", f->received}, {"missing", f->missing}, {"duplicated", f->duplicated},
                   {"reordered", f->reordered}};
      }
      j["topics"].push_back({{"topic", t.topic},
                             {"type", t.type},
                             {"messages", t.messages},
                             {"rate_hz", t.rate_hz ? nlohmann::ordered_json(*t.rate_hz) : nlohmann::ordered_json(nullptr)},
                             {"loss", figures}});
    }
    std::printf("%s\n", j.dump(2).c_str());
    return c.complete ? 0 : 1;
  }
  std::printf("file:      %s%s\n", file.c_str(), c.complete ? "" : " (INCOMPLETE: quad bag recover can rewrite it)");
  if (!c.complete) {
    std::printf("problem:   %s\n", c.problem.c_str());
  }
  std::printf("messages:  %zu in %u chunks, %zu channels, %.3f s\n", c.messages.size(), c.chunks, c.channels.size(), span);
  std::printf("%-26s %-28s %9s %9s  %s\n", "TOPIC", "TYPE", "MESSAGES", "RATE", "LOSS (from Header.seq per writer)");
  for (const Topic& t : topics) {
    const std::string rate = t.rate_hz ? fmt::format("{:.1f} Hz", *t.rate_hz) : "-";
    std::printf("%-26s %-28s %9llu %9s  %s\n", t.topic.c_str(), t.type.c_str(), static_cast<unsigned long long>(t.messages),
                rate.c_str(), t.loss ? t.loss->c_str() : t.type.starts_with("quad::msg::") ? "(not recorded)" : "(no Header to audit)");
  }
  return c.complete ? 0 : 1;
}

int bagEcho(const BagEchoOptions& options)
{
  bag::McapContents c;
  try {
    c = bag::readMcap(options.file, true);
  } catch (const bag::BagError& e) {
    std::fprintf(stderr, "bag echo: %s\n", e.what());
    return 1;
  }
  std::map<std::uint16_t, std::string> schema_names;
  for (const auto& sc : c.schemas) {
    schema_names[sc.id] = sc.name;
  }
  std::map<std::uint16_t, std::pair<std::string, std::string>> channels;  // id: topic, type
  for (const auto& ch : c.channels) {
    if (options.topics.empty() || topic::matchesAnyGlob(ch.topic, options.topics)) {
      channels[ch.id] = {ch.topic, schema_names[ch.schema_id]};
    }
  }
  std::vector<const bag::Message*> messages;
  for (const auto& m : c.messages) {
    if (channels.count(m.channel_id) != 0) {
      messages.push_back(&m);
    }
  }
  std::stable_sort(messages.begin(), messages.end(),
                   [](const bag::Message* a, const bag::Message* b) { return a->log_time < b->log_time; });
  const auto& schema = introspection::quadSchema();
  const introspection::DecodeOptions decode{
      .max_elements = options.max_elements > 0 ? options.max_elements : std::numeric_limits<std::size_t>::max()};
  int bad = 0;
  for (const bag::Message* m : messages) {
    const auto& [name, type] = channels[m->channel_id];
    nlohmann::ordered_json line;
    line["topic"] = name;
    line["log_time_ns"] = m->log_time;
    try {
      line["message"] = introspection::decodeCdr(schema, type, m->data, decode);
    } catch (const std::exception& e) {
      ++bad;
      std::fprintf(stderr, "bag echo: %s: message %u on %s (%s): %s\n", options.file.c_str(), m->sequence,
                   name.c_str(), type.c_str(), e.what());
      continue;
    }
    if (options.json) {
      std::printf("%s\n", line.dump().c_str());
    } else {
      std::printf("%s---\n", topic::toYaml(line).c_str());
    }
  }
  if (!c.complete) {
    std::fprintf(stderr, "bag echo: %s: read up to a damage (%s)\n", options.file.c_str(), c.problem.c_str());
  }
  return bad > 0 ? 1 : 0;
}

int bagRecover(const std::string& file, std::string output)
{
  if (output.empty()) {
    output = (file.ends_with(".mcap") ? file.substr(0, file.size() - 5) : file) + ".recovered.mcap";
  }
  try {
    const auto c = bag::recoverMcap(file, output);
    std::printf("%s: %zu messages on %zu channels%s\n", output.c_str(), c.messages.size(), c.channels.size(),
                c.problem.empty() ? " (the file was whole)" : (" (reading stopped: " + c.problem + ")").c_str());
  } catch (const bag::BagError& e) {
    std::fprintf(stderr, "bag recover: %s\n", e.what());
    return 1;
  }
  return 0;
}

int bagDiff(const BagDiffOptions& options)
{
  bag::McapContents first, second;
  try {
    first = bag::readMcap(options.first);
    second = bag::readMcap(options.second);
  } catch (const bag::BagError& e) {
    std::fprintf(stderr, "bag diff: %s\n", e.what());
    return 2;
  }
  const bag::Comparison c = bag::compareRecordings(first, second, simPacedComparison([&](const std::string& topic) {
    if (!options.topics.empty() && !topic::matchesAnyGlob(topic, options.topics)) {
      return false;
    }
    if (topic::matchesAnyGlob(topic, options.exclude)) {
      return false;
    }
    return options.all_topics || dds::topics::isSimPaced(topic);
  }));
  printComparison(c, options.json);
  return c.differences.empty() ? 0 : 1;
}

}  // namespace quad::tools
