// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/run_record.hpp"

#include <array>
#include <fstream>

#include <nlohmann/json.hpp>

namespace quad::launch {

namespace {
// Indexed by the enumerators, in their order.
constexpr std::array<std::string_view, 7> kModulePhases{"waiting", "starting", "running", "restarting",
                                                        "exited",  "failed",   "stopped"};
constexpr std::array<std::string_view, 4> kRunPhases{"starting", "running", "stopping", "ended"};
}  // namespace

std::string_view toString(ModulePhase phase) { return kModulePhases.at(static_cast<std::size_t>(phase)); }

std::string_view toString(RunPhase phase) { return kRunPhases.at(static_cast<std::size_t>(phase)); }

std::string toJson(const RunRecord& r)
{
  nlohmann::ordered_json j;
  j["manifest"] = r.manifest;
  j["world"] = r.world;
  j["domain"] = r.domain;
  j["phase"] = toString(r.phase);
  j["failure"] = r.failure;
  j["exit_code"] = r.exit_code ? nlohmann::ordered_json(*r.exit_code) : nlohmann::ordered_json(nullptr);
  j["discovery_server"] = r.discovery_server;
  j["firewall"] = r.firewall;
  nlohmann::ordered_json hosts = nlohmann::ordered_json::object();
  for (const auto& [name, h] : r.hosts) {
    hosts[name] = {{"kind", h.kind}, {"address", h.address}, {"namespace", h.network_namespace}};
  }
  j["hosts"] = hosts;
  nlohmann::ordered_json modules = nlohmann::ordered_json::object();
  for (const auto& name : r.order) {
    const auto it = r.modules.find(name);
    if (it == r.modules.end()) {
      continue;
    }
    const ModuleRecord& m = it->second;
    modules[name] = {{"kind", m.kind},         {"host", m.host},         {"phase", toString(m.phase)},
                     {"pid", m.pid},           {"starts", m.starts},     {"restarts", m.restarts},
                     {"last_exit", m.last_exit}, {"started_ns", m.started_ns}, {"command", m.command}};
    if (!m.hosted.empty()) {
      modules[name]["hosted"] = m.hosted;
    }
  }
  j["modules"] = modules;
  j["stopped_order"] = r.stopped_order;
  return j.dump(2) + "\n";
}

bool writeRunRecord(const std::filesystem::path& file, const RunRecord& record)
{
  std::filesystem::path partial = file;
  partial += ".partial";
  {
    std::ofstream out(partial, std::ios::trunc);
    out << toJson(record);
    if (!out) {
      return false;
    }
  }
  std::error_code ec;
  std::filesystem::rename(partial, file, ec);
  return !ec;
}

}  // namespace quad::launch
