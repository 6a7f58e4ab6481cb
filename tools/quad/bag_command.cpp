#include <cstdio>
#include <map>

#include <fmt/format.h>

#include "bag_commands.hpp"
#include "quad/bag/audit.hpp"
#include "quad/bag/mcap.hpp"

namespace quad::tools {

int bagInfo(const std::string& file)
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
  std::printf("file:      %s%s\n", file.c_str(), c.complete ? "" : " (INCOMPLETE: quad bag recover can rewrite it)");
  if (!c.complete) {
    std::printf("problem:   %s\n", c.problem.c_str());
  }
  std::printf("messages:  %zu in %u chunks, %zu channels, %.3f s\n", c.messages.size(), c.chunks, c.channels.size(), span);
  std::printf("%-26s %-28s %9s %9s  %s\n", "TOPIC", "TYPE", "MESSAGES", "RATE", "LOSS (from Header.seq per writer)");
  for (const auto& [id, ch] : channels) {
    const Row r = rows[id];
    const double s = static_cast<double>(r.last - r.first) * 1e-9;
    const std::string rate = r.count > 1 && s > 0 ? fmt::format("{:.1f} Hz", static_cast<double>(r.count - 1) / s) : "-";
    const auto schema_it = schemas.find(ch->schema_id);
    const std::string type = schema_it == schemas.end() ? "?" : schema_it->second->name;
    const auto l = loss.find(ch->topic);
    std::printf("%-26s %-28s %9llu %9s  %s\n", ch->topic.c_str(), type.c_str(), static_cast<unsigned long long>(r.count),
                rate.c_str(), l == loss.end() ? "(not recorded)" : l->second.c_str());
  }
  return c.complete ? 0 : 1;
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

}  // namespace quad::tools
