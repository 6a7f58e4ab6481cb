// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/manifest.hpp"

#include "containers.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <regex>
#include <set>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "quad/common/params.hpp"
#include "quad/common/payload_header.hpp"
#include "quad/common/yaml_input.hpp"

namespace quad::launch {

std::string_view toString(HostKind kind)
{
  constexpr std::array<std::string_view, 3> kNames{"local", "netns", "ssh"};  // by the enumerators' order
  return kNames.at(static_cast<std::size_t>(kind));
}

namespace fs = std::filesystem;

const Host& Manifest::host(const std::string& host_name) const
{
  for (const auto& h : hosts) {
    if (h.name == host_name) {
      return h;
    }
  }
  throw std::out_of_range("no host '" + host_name + "' in " + file.string());
}

std::vector<const Module*> Manifest::hostedModules() const
{
  std::vector<const Module*> out;
  for (const Module& mod : modules) {
    if (mod.hosted.empty()) {
      out.push_back(&mod);
    }
    for (const Module& hosted : mod.hosted) {
      out.push_back(&hosted);
    }
  }
  return out;
}

Module* Manifest::findHostedModule(const std::string& module_name)
{
  for (Module& mod : modules) {
    if (mod.hosted.empty() && mod.name == module_name) {
      return &mod;
    }
    for (Module& hosted : mod.hosted) {
      if (hosted.name == module_name) {
        return &hosted;
      }
    }
  }
  return nullptr;
}

const Module* Manifest::processOf(const std::string& module_name) const
{
  for (const Module& mod : modules) {
    const bool hosting = std::any_of(mod.hosted.begin(), mod.hosted.end(),
                                     [&](const Module& h) { return h.name == module_name; });
    if ((mod.hosted.empty() && mod.name == module_name) || hosting) {
      return &mod;
    }
  }
  return nullptr;
}

const Module* Manifest::findModule(const std::string& module_name) const
{
  const auto it = std::find_if(modules.begin(), modules.end(), [&](const Module& m) { return m.name == module_name; });
  return it == modules.end() ? nullptr : &*it;
}

bool Manifest::usesNamespaces() const
{
  return std::any_of(hosts.begin(), hosts.end(), [](const Host& h) { return h.kind == HostKind::kNetns; });
}

std::vector<std::uint32_t> Manifest::vehicleIds() const
{
  std::vector<std::uint32_t> ids;
  for (const FleetMember& v : vehicles) {
    ids.push_back(v.id);
  }
  return ids.empty() ? std::vector<std::uint32_t>{0} : ids;
}

std::string fleetInstanceName(const std::string& module_name, std::uint32_t vehicle_id)
{
  return module_name + "." + std::to_string(vehicle_id);
}

std::string vehicleFolder(std::uint32_t vehicle_id) { return "vehicle" + std::to_string(vehicle_id); }

std::string fleetFileText(const std::vector<FleetMember>& vehicles)
{
  const auto point = [](const std::array<double, 3>& p) { return fmt::format("[{}, {}, {}]", p[0], p[1], p[2]); };
  std::string text = "# Written by quad launch from the manifest's vehicles.\nvehicles:\n";
  for (const FleetMember& v : vehicles) {
    text += fmt::format("  - {{id: {}, start: {}", v.id, point(v.start));
    if (v.goal) {
      text += ", goal: " + point(*v.goal);
    }
    if (!v.vehicle.empty()) {
      text += ", vehicle: \"" + v.vehicle.string() + "\"";
    }
    text += "}\n";
  }
  return text;
}

namespace {

/// The modules that act on the manifest's geofence.
const std::set<std::string> kGeofenceModules{"planning", "control"};

/// The modules quad builds, by the name a manifest gives them.
const std::map<std::string, std::string> kBuiltModules{
    {"plant", "modules/plant/node/quad_plant_node"},
    {"estimation", "modules/estimation/node/quad_estimation_node"},
    {"mapping", "modules/mapping/node/quad_mapping_node"},
    {"planning", "modules/planning/node/quad_planning_node"},
    {"control", "modules/control/node/quad_control_node"},
    {"display", "modules/display/node/quad_display_node"},
    {"quad", "tools/quad/quad"},
};

/// The program that hosts several modules (the composed layout).
constexpr const char* kContainerProgram = "tools/container/quad_container";

class Reader : public common::YamlReader {
public:
  Reader(std::string_view origin, fs::path dir) : YamlReader(origin), dir_(std::move(dir)) {}

  std::optional<std::string> choice(const YAML::Node& node, const std::string& key, const std::string& fallback,
                                    const std::set<std::string>& allowed)
  {
    auto t = text(node, key, fallback);
    if (t && !allowed.contains(*t)) {
      std::string list;
      for (const auto& a : allowed) {
        list += (list.empty() ? "" : ", ") + a;
      }
      problem(key, node, "expected one of: " + list);
      return std::nullopt;
    }
    return t;
  }

  std::vector<std::string> strings(const YAML::Node& node, const std::string& key)
  {
    std::vector<std::string> out;
    if (!node) {
      return out;
    }
    if (!node.IsSequence()) {
      problem(key, node, "expected a list");
      return out;
    }
    for (std::size_t i = 0; i < node.size(); ++i) {
      if (auto t = text(node[i], key + "[" + std::to_string(i) + "]", std::nullopt)) {
        out.push_back(*t);
      }
    }
    return out;
  }


  fs::path path(const std::string& written) const
  {
    const fs::path p(written);
    return p.is_absolute() ? p : (dir_ / p).lexically_normal();
  }

private:
  fs::path dir_;
};

/// Replaces ${name} with its value; an unknown name is a problem.
std::string expand(const std::string& text, const std::map<std::string, std::string>& vars, Reader& r,
                   const std::string& key, const YAML::Node& node)
{
  static const std::regex var(R"(\$\{([A-Za-z_]+)\})");
  std::string out;
  auto begin = std::sregex_iterator(text.begin(), text.end(), var);
  std::size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    out += text.substr(last, static_cast<std::size_t>(it->position()) - last);
    const auto found = vars.find((*it)[1].str());
    if (found == vars.end()) {
      r.problem(key, node, "unknown variable ${" + (*it)[1].str() + "} (known: world, mode, seed, root, run_state)");
    } else {
      out += found->second;
    }
    last = static_cast<std::size_t>(it->position() + it->length());
  }
  return out + text.substr(last);
}

bool isIpv4(const std::string& text)
{
  in_addr addr{};
  return inet_pton(AF_INET, text.c_str(), &addr) == 1;
}

bool validName(const std::string& name)
{
  static const std::regex re("[a-z][a-z0-9_]{0,14}");
  return std::regex_match(name, re);
}

void readHosts(YAML::Node node, Reader& r, Manifest& m)
{
  if (!node) {
    m.hosts.push_back(Host{"local", HostKind::kLocal, "", 22, "", {}});
    return;
  }
  if (!node.IsMap() || node.size() == 0) {
    r.problem("hosts", node, "expected a map of host names to hosts");
    return;
  }
  for (auto kv : node) {
    Host h;
    h.name = kv.first.as<std::string>();
    const std::string key = "hosts." + h.name;
    YAML::Node spec = kv.second;
    if (!validName(h.name)) {
      r.problem(key, kv.first, "a host name is lower case letters, digits and _, at most 15");
    }
    if (!spec.IsMap()) {
      r.problem(key, spec, "expected a map with 'type'");
      continue;
    }
    r.onlyKeys(spec, key + ".", {"type", "address", "port", "root", "options", "interfaces"});
    const auto type = r.choice(spec["type"], key + ".type", "local",
                                      {std::string(toString(HostKind::kLocal)), std::string(toString(HostKind::kNetns)),
                                       std::string(toString(HostKind::kSsh))});
    if (type == toString(HostKind::kNetns)) {
      h.kind = HostKind::kNetns;
    } else if (type == toString(HostKind::kSsh)) {
      h.kind = HostKind::kSsh;
      h.address = r.text(spec["address"], key + ".address", std::nullopt).value_or("");
      h.ssh_port = static_cast<int>(r.number(spec["port"], key + ".port", 22, 1, 65535).value_or(22));
      h.root = r.text(spec["root"], key + ".root", std::string()).value_or("");
      h.ssh_options = r.strings(spec["options"], key + ".options");
    }
    h.interfaces = r.strings(spec["interfaces"], key + ".interfaces");
    for (std::size_t i = 0; i < h.interfaces.size(); ++i) {
      if (!isIpv4(h.interfaces[i])) {
        r.problem(key + ".interfaces[" + std::to_string(i) + "]", spec["interfaces"][i], "not an IPv4 address");
      }
    }
    if (h.kind != HostKind::kSsh) {
      for (const char* k : {"address", "port", "root", "options"}) {
        if (spec[k]) {
          r.problem(key + "." + k, spec[k], "only an ssh host takes this key");
        }
      }
    }
    m.hosts.push_back(h);
  }
}

/// `network:` what DDS may use on each host, and the firewall quad launch installs.
void readNetwork(const YAML::Node& node, Reader& r, Manifest& m)
{
  if (!node) {
    return;
  }
  if (!node.IsMap()) {
    r.problem("network", node, "expected a map with interfaces and/or firewall");
    return;
  }
  r.onlyKeys(node, "network.", {"interfaces", "firewall"});
  m.restrict_interfaces = r.choice(node["interfaces"], "network.interfaces", "any", {"any", "hosts"}) == "hosts";
  m.firewall = r.flag(node["firewall"], "network.firewall", false).value_or(false);
  if (m.restrict_interfaces) {
    if (m.transport == "shm") {
      r.problem("network.interfaces", node["interfaces"], "restricts UDP, and the transport is shm");
    }
    for (const auto& h : m.hosts) {
      const std::string address = h.address.substr(h.address.find('@') + 1);
      if (h.kind == HostKind::kSsh && h.interfaces.empty() && !isIpv4(address)) {
        r.problem("hosts." + h.name + ".interfaces", node["interfaces"],
                  "network.interfaces: hosts needs this ssh host's IPv4 addresses (its address " + h.address +
                      " is a name)");
      }
    }
  }
  if (m.firewall && std::none_of(m.hosts.begin(), m.hosts.end(), [](const Host& h) { return h.kind != HostKind::kLocal; })) {
    r.problem("network.firewall", node["firewall"],
              "no netns or ssh host to install it on (quad launch leaves this machine's own firewall alone)");
  }
}

void readModule(const std::string& name, YAML::Node spec, Reader& r, const ProgramLookup& lookup,
                const std::map<std::string, std::string>& vars, Manifest& m)
{
  const std::string key = "modules." + name;
  Module mod;
  mod.name = name;
  if (!validName(name)) {
    r.problem(key, YAML::Node(name), "a module name is lower case letters, digits and _, at most 15");
  }
  if (!spec.IsMap()) {
    r.problem(key, spec, "expected a map");
    return;
  }
  r.onlyKeys(spec, key + ".", {"module", "program", "host", "config", "set", "args", "env", "needs",
                         "ready_timeout", "respawn", "backoff", "ends_run"});
  // The program: a module quad builds, or any program by path.
  if (spec["program"] && spec["module"]) {
    r.problem(key + ".program", spec["program"], "give 'module' or 'program', not both");
  } else if (spec["program"]) {
    mod.program = r.path(expand(r.text(spec["program"], key + ".program", "").value_or(""), vars, r,
                                key + ".program", spec["program"]));
    if (!fs::exists(mod.program)) {
      r.problem(key + ".program", spec["program"], "no such program (" + mod.program.string() + ")");
    }
  } else {
    const std::string which = r.text(spec["module"], key + ".module", name).value_or(name);
    const auto built = kBuiltModules.find(which);
    if (built == kBuiltModules.end()) {
      std::string list;
      for (const auto& [n, p] : kBuiltModules) {
        list += (list.empty() ? "" : ", ") + n;
      }
      r.problem(key + ".module", spec["module"] ? spec["module"] : YAML::Node(which),
                "module not found: quad builds " + list + " (or give 'program')");
    } else {
      mod.kind = which;
      mod.program = common::programPath(lookup.layout, built->second);
      if (!fs::exists(mod.program)) {
        r.problem(key + ".module", YAML::Node(which), "module not built: no " + mod.program.string());
      }
    }
  }
  const std::string host = r.text(spec["host"], key + ".host", m.hosts.front().name).value_or("");
  if (std::none_of(m.hosts.begin(), m.hosts.end(), [&](const Host& h) { return h.name == host; })) {
    std::string list;
    for (const auto& h : m.hosts) {
      list += (list.empty() ? "" : ", ") + h.name;
    }
    r.problem(key + ".host", spec["host"], "unknown host (hosts: " + list + ")");
  }
  mod.host = host;
  if (spec["config"]) {
    mod.config = r.path(expand(r.text(spec["config"], key + ".config", "").value_or(""), vars, r, key + ".config",
                               spec["config"]));
    if (!fs::is_regular_file(mod.config)) {
      r.problem(key + ".config", spec["config"], "no such file (" + mod.config.string() + ")");
    }
  }
  for (const auto& [k, v] : r.scalars(spec["set"], key + ".set")) {
    mod.sets.emplace_back(k, expand(v, vars, r, key + ".set." + k, spec["set"][k]));
  }
  for (const auto& a : r.strings(spec["args"], key + ".args")) {
    mod.args.push_back(expand(a, vars, r, key + ".args", spec["args"]));
  }
  for (const auto& [k, v] : r.scalars(spec["env"], key + ".env")) {
    mod.environment[k] = expand(v, vars, r, key + ".env." + k, spec["env"][k]);
  }
  mod.needs = r.strings(spec["needs"], key + ".needs");
  for (std::size_t i = 0; i < mod.needs.size(); ++i) {
    if (lookup.topic_owner && !lookup.topic_owner(mod.needs[i])) {
      r.problem(key + ".needs[" + std::to_string(i) + "]", spec["needs"][i], "no such topic (see quad topic list --contracts)");
    }
  }
  mod.ready_timeout_s = r.number(spec["ready_timeout"], key + ".ready_timeout", 20.0, 0.1, 3600.0).value_or(20.0);
  mod.respawn = static_cast<int>(r.number(spec["respawn"], key + ".respawn", 0, 0, 100).value_or(0));
  mod.backoff_s = r.number(spec["backoff"], key + ".backoff", 1.0, 0.0, 600.0).value_or(1.0);
  mod.ends_run = r.flag(spec["ends_run"], key + ".ends_run", false).value_or(false);
  // The manifest's geofence reaches the modules that act on it; one given to a module alone
  // would leave the others without it.
  if (kGeofenceModules.contains(mod.kind)) {
    for (const auto& [k, v] : common::geofenceSets(m.geofence.value_or(common::Geofence{}))) {
      if (spec["set"] && spec["set"][k]) {
        r.problem(key + ".set." + k, spec["set"][k], "give the run's keep-in volume as the manifest's geofence");
      } else if (m.geofence) {
        mod.sets.emplace_back(k, v);
      }
    }
  }
  m.modules.push_back(std::move(mod));
}

/// The command line's `--set MODULE:KEY=VALUE`, each replacing the module's `set` of that key
/// or added to them; a module the manifest does not have is a problem naming it.
void applyModuleSets(const std::vector<ModuleSet>& sets, Reader& r, Manifest& m)
{
  for (const ModuleSet& s : sets) {
    const auto mod = std::find_if(m.modules.begin(), m.modules.end(), [&](const Module& x) { return x.name == s.module; });
    if (mod == m.modules.end()) {
      std::vector<std::string> names;
      for (const Module& x : m.modules) {
        names.push_back(x.name);
      }
      r.problem("--set " + s.module + ":" + s.key, YAML::Node(s.value),
                fmt::format("no module '{}' in the manifest (modules: {})", s.module, fmt::join(names, ", ")));
      continue;
    }
    const auto set = std::find_if(mod->sets.begin(), mod->sets.end(), [&](const auto& kv) { return kv.first == s.key; });
    if (set != mod->sets.end()) {
      set->second = s.value;
    } else {
      mod->sets.emplace_back(s.key, s.value);
    }
  }
}

/// `vehicles:` a fleet, each vehicle with its id, start, goal, vehicle file and the hosts of
/// its modules (module name to host; the module's own host for the others).
std::map<std::uint32_t, std::map<std::string, std::string>> readVehicles(YAML::Node node, Reader& r, Manifest& m)
{
  std::map<std::uint32_t, std::map<std::string, std::string>> hosts_of;
  if (!node) {
    return hosts_of;
  }
  if (!node.IsSequence() || node.size() == 0) {
    r.problem("vehicles", node, "expected a list of vehicles, each with id and start");
    return hosts_of;
  }
  if (node.size() > static_cast<std::size_t>(common::kMaxFleetVehicles)) {
    r.problem("vehicles", YAML::Node(std::to_string(node.size()) + " vehicles"),
              "at most " + std::to_string(common::kMaxFleetVehicles) + " fly in one domain");
    return hosts_of;
  }
  std::map<std::uint32_t, std::string> key_of_id;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string key = "vehicles[" + std::to_string(i) + "]";
    YAML::Node item = node[i];
    if (!item.IsMap()) {
      r.problem(key, item, "expected a map with id and start");
      continue;
    }
    r.onlyKeys(item, key + ".", {"id", "start", "goal", "vehicle", "hosts"});
    FleetMember v;
    const auto id = r.number(item["id"], key + ".id", std::nullopt, 0.0, common::kMaxVehicleId);
    if (id && *id != std::floor(*id)) {
      r.problem(key + ".id", item["id"], "expected a whole number");
    } else if (id) {
      v.id = static_cast<std::uint32_t>(*id);
      if (const auto [it, fresh] = key_of_id.emplace(v.id, key); !fresh) {
        r.problem(key + ".id", item["id"], "already the id of " + it->second);
      }
    }
    const auto point = [&](const char* name) -> std::optional<std::array<double, 3>> {
      const auto p = r.numbers(item[name], key + "." + name, 3, -1e6, 1e6);
      return p ? std::optional<std::array<double, 3>>({(*p)[0], (*p)[1], (*p)[2]}) : std::nullopt;
    };
    v.start = point("start").value_or(std::array<double, 3>{});
    if (item["goal"]) {
      v.goal = point("goal");
    }
    if (item["vehicle"]) {
      v.vehicle = r.path(r.text(item["vehicle"], key + ".vehicle", "").value_or(""));
      if (!fs::is_regular_file(v.vehicle)) {
        r.problem(key + ".vehicle", item["vehicle"], "no such file");
      }
    } else {
      v.vehicle = m.mission.vehicle;
    }
    std::map<std::string, std::string>& hosts = hosts_of[v.id];
    for (const auto& [module_name, host] : r.scalars(item["hosts"], key + ".hosts")) {
      const std::string host_key = key + ".hosts." + module_name;
      if (std::none_of(m.hosts.begin(), m.hosts.end(), [&](const Host& h) { return h.name == host; })) {
        r.problem(host_key, item["hosts"][module_name], "unknown host");
      } else if (m.findModule(module_name) == nullptr) {
        r.problem(host_key, item["hosts"][module_name], "no module '" + module_name + "' in modules");
      } else {
        hosts[module_name] = host;
      }
    }
    m.vehicles.push_back(std::move(v));
  }
  return hosts_of;
}

/// A fleet's modules: the plant once, for every vehicle (it reads the fleet file the launcher
/// writes), each other module once per vehicle, with a state folder of its own.
void expandFleet(const YAML::Node& root, Reader& r, Manifest& m,
                 const std::map<std::uint32_t, std::map<std::string, std::string>>& hosts_of)
{
  const auto plants = std::count_if(m.modules.begin(), m.modules.end(), [](const Module& x) { return x.kind == "plant"; });
  if (plants != 1) {
    r.problem("vehicles", root["vehicles"], "a fleet is simulated by one plant module; the manifest has " +
                                                std::to_string(plants));
    return;
  }
  if (m.world.empty()) {
    r.problem("vehicles", root["vehicles"], "a fleet flies in a world: give 'world'");
  }
  std::vector<Module> expanded;
  for (const Module& mod : m.modules) {
    if (mod.kind == "plant") {
      Module plant = mod;
      if (std::any_of(plant.sets.begin(), plant.sets.end(), [](const auto& kv) { return kv.first == "fleet"; })) {
        r.problem("modules." + mod.name + ".set.fleet", root["modules"][mod.name]["set"]["fleet"],
                  "the launcher writes the plant's fleet file from the manifest's vehicles");
      }
      plant.sets.emplace_back("fleet", std::string(kRunStateVariable) + "/" + kFleetFile);
      expanded.push_back(std::move(plant));
      continue;
    }
    for (const FleetMember& v : m.vehicles) {
      Module one = mod;
      one.name = fleetInstanceName(mod.name, v.id);
      one.vehicle = v.id;
      const std::string own_state = std::string(kRunStateVariable) + "/" + vehicleFolder(v.id);
      const auto ownState = [&](std::string& text) { text = withRunState(text, own_state); };
      for (auto& kv : one.sets) {
        ownState(kv.second);
      }
      for (auto& a : one.args) {
        ownState(a);
      }
      for (auto& kv : one.environment) {
        ownState(kv.second);
      }
      if (const auto host = hosts_of.find(v.id); host != hosts_of.end()) {
        if (const auto it = host->second.find(mod.name); it != host->second.end()) {
          one.host = it->second;
        }
      }
      expanded.push_back(std::move(one));
    }
  }
  m.modules = std::move(expanded);
}

/// `containers:` which modules share a process in the composed layout (a map of names to
/// lists of module names), checked against the modules; in that layout, each becomes one
/// Module in its first module's place.
void readContainers(const YAML::Node& node, Reader& r, const ProgramLookup& lookup, Manifest& m)
{
  if (!node) {
    if (m.layout == "composed") {
      r.problem("layout", YAML::Node(m.layout), "the composed layout hosts the modules of 'containers', and there are none");
    }
    return;
  }
  if (!node.IsMap() || node.size() == 0) {
    r.problem("containers", node, "expected a map of container names to lists of modules");
    return;
  }
  // A fleet's containers are a vehicle's: the lists name the manifest's modules, and each
  // container is made once per vehicle, of that vehicle's instances ("slow.2": mapping.2 and
  // planning.2). The plant, which serves every vehicle, stays a process of its own.
  const bool fleet = !m.vehicles.empty();
  const auto instance = [&](const std::string& name) {
    return fleet ? fleetInstanceName(name, m.vehicles.front().id) : name;
  };
  std::map<std::string, std::string> listed_in;  // a module as the lists name it, and its container
  std::vector<ContainerSpec> specs;
  for (auto kv : node) {
    ContainerSpec spec{kv.first.as<std::string>(), {}};
    const std::string key = "containers." + spec.name;
    if (!validName(spec.name)) {
      r.problem(key, kv.first, "a container name is lower case letters, digits and _, at most 15");
    } else if (m.findModule(spec.name) != nullptr || m.findModule(instance(spec.name)) != nullptr) {
      r.problem(key, kv.first, "already a module's name: a container's process needs one of its own");
    }
    spec.modules = r.strings(kv.second, key);
    if (kv.second.IsSequence() && spec.modules.empty()) {
      r.problem(key, kv.second, "expected at least one module");
    }
    for (std::size_t i = 0; i < spec.modules.size(); ++i) {
      const std::string& name = spec.modules[i];
      const std::string item = key + "[" + std::to_string(i) + "]";
      const Module* mod = m.findModule(instance(name));
      if (mod == nullptr && fleet && m.findModule(name) != nullptr) {
        r.problem(item, kv.second[i],
                  "'" + name + "' serves every vehicle of the fleet: a fleet's container holds one vehicle's modules");
      } else if (mod == nullptr) {
        r.problem(item, kv.second[i], "no module '" + name + "' in modules");
      } else if (mod->kind.empty() || mod->kind == "quad") {
        r.problem(item, kv.second[i], "'" + name + "' is a program, not one of quad's modules: only those can share a process");
      } else if (const auto [it, fresh] = listed_in.emplace(name, spec.name); !fresh) {
        r.problem(item, kv.second[i], "'" + name + "' is already in container " + it->second);
      }
    }
    specs.push_back(std::move(spec));
  }
  std::map<std::string, std::string> written_as;  // a container's name as the manifest writes it
  for (const ContainerSpec& spec : specs) {
    if (!fleet) {
      written_as.emplace(spec.name, spec.name);
      m.containers.push_back(spec);
      continue;
    }
    for (const FleetMember& v : m.vehicles) {
      ContainerSpec one{fleetInstanceName(spec.name, v.id), {}};
      written_as.emplace(one.name, spec.name);
      for (const auto& name : spec.modules) {
        one.modules.push_back(fleetInstanceName(name, v.id));
      }
      m.containers.push_back(std::move(one));
    }
  }
  std::map<std::string, std::string> container_of;  // a module (a fleet's: an instance), and its container
  for (const ContainerSpec& spec : m.containers) {
    for (const auto& name : spec.modules) {
      container_of.emplace(name, spec.name);
    }
  }
  if (m.layout != "composed" || !r.ok()) {
    return;
  }
  const fs::path program = common::programPath(lookup.layout, kContainerProgram);
  if (!fs::exists(program)) {
    r.problem("layout", YAML::Node(m.layout), "the container program is not built: no " + program.string());
    return;
  }
  std::vector<Module> composed;
  for (const Module& mod : m.modules) {
    const auto in = container_of.find(mod.name);
    if (in == container_of.end()) {
      composed.push_back(mod);
      continue;
    }
    const auto spec = std::find_if(m.containers.begin(), m.containers.end(),
                                   [&](const ContainerSpec& c) { return c.name == in->second; });
    if (std::any_of(composed.begin(), composed.end(), [&](const Module& c) { return c.name == spec->name; })) {
      continue;  // placed with its first module
    }
    std::vector<const Module*> members;
    for (const Module& other : m.modules) {
      if (container_of.contains(other.name) && container_of.at(other.name) == spec->name) {
        members.push_back(&other);
      }
    }
    std::vector<std::string> problems;
    composed.push_back(composeContainer(*spec, members, program, lookup, problems));
    if (!m.security_dir.empty()) {
      checkContainerIdentity(composed.back(), m.security_dir, problems);
    }
    for (const auto& problem : problems) {
      r.problem("containers." + spec->name, node[written_as.at(spec->name)], problem);
    }
  }
  m.modules = std::move(composed);
}

}  // namespace

Manifest parseManifest(const std::string& text, const fs::path& origin, const ManifestOverrides& overrides,
                       const ProgramLookup& lookup)
{
  YAML::Node root = common::parseYaml(text, origin.string());
  Reader r(origin.string(), origin.parent_path());
  Manifest m;
  m.file = origin;
  if (!root.IsMap()) {
    r.problem("(top level)", root, "expected a map with 'modules'");
    r.throwIfAny();
  }
  r.onlyKeys(root, "", {"name", "domain", "transport", "discovery", "subnet", "world", "mode", "state", "seed", "grace", "env",
                        "security", "network", "hosts", "modules", "mission", "geofence", "vehicles", "layout",
                        "containers"});
  m.name = r.text(root["name"], "name", origin.stem().string()).value_or("run");
  if (overrides.domain) {
    m.domain = overrides.domain;
  } else if (root["domain"]) {
    m.domain = static_cast<int>(r.number(root["domain"], "domain", 0, 0, 232).value_or(0));
  }
  m.transport = r.choice(root["transport"], "transport", "udp", {"udp", "shm", "default"}).value_or("udp");
  m.grace_s = r.number(root["grace"], "grace", 5.0, 0.1, 600.0).value_or(5.0);
  m.subnet = overrides.subnet ? *overrides.subnet : r.text(root["subnet"], "subnet", "10.77.0").value_or("10.77.0");
  if (!std::regex_match(m.subnet, std::regex(R"((\d{1,3})\.(\d{1,3})\.(\d{1,3}))"))) {
    r.problem("subnet", root["subnet"], "expected the first three numbers of an IPv4 /24, e.g. 10.77.0");
  }
  readHosts(root["hosts"], r, m);

  // Discovery.
  if (YAML::Node d = root["discovery"]; d) {
    r.onlyKeys(d, "discovery.", {"kind", "host", "port", "lease"});
    const auto kind = r.choice(d["kind"], "discovery.kind", "multicast", {"multicast", "initial_peers", "server"});
    m.discovery = kind == "server" ? Discovery::kServer
                  : kind == "initial_peers" ? Discovery::kInitialPeers
                                            : Discovery::kMulticast;
    m.discovery_port = static_cast<int>(r.number(d["port"], "discovery.port", 11811, 1024, 65535).value_or(11811));
    if (const auto lease = r.number(d["lease"], "discovery.lease", 0.0, 1.0, 86400.0); lease && *lease != 0.0) {
      if (*lease != std::floor(*lease)) {
        r.problem("discovery.lease", d["lease"], "expected whole seconds");
      }
      m.participant_lease_s = static_cast<int>(*lease);
    }
    if (m.discovery == Discovery::kServer && !m.hosts.empty()) {
      m.discovery_host = r.text(d["host"], "discovery.host", m.hosts.front().name).value_or("");
      if (std::none_of(m.hosts.begin(), m.hosts.end(), [&](const Host& h) { return h.name == m.discovery_host; })) {
        r.problem("discovery.host", d["host"], "unknown host");
      }
    } else if (d["host"]) {
      r.problem("discovery.host", d["host"], "only a discovery server has a host");
    }
  }

  readNetwork(root["network"], r, m);

  // Variables, then modules.
  if (overrides.world) {
    m.world = fs::absolute(*overrides.world).lexically_normal();
  } else if (root["world"]) {
    m.world = r.path(r.text(root["world"], "world", "").value_or(""));
  }
  if (!m.world.empty() && !fs::is_regular_file(m.world)) {
    r.problem("world", root["world"] ? root["world"] : YAML::Node(m.world.string()), "no such file");
  }
  if (root["security"]) {
    m.security_dir = r.path(r.text(root["security"], "security", "").value_or(""));
    for (const char* file : {"ca.pem", "governance.p7s"}) {
      if (!fs::is_regular_file(m.security_dir / file)) {
        r.problem("security", root["security"],
                  "no " + std::string(file) + " in " + m.security_dir.string() + ": make it with quad security init " +
                      m.security_dir.string());
        break;
      }
    }
  }
  m.mode = overrides.mode ? *overrides.mode : r.choice(root["mode"], "mode", "lockstep", {"lockstep", "realtime"}).value_or("lockstep");
  m.state = overrides.state ? *overrides.state
                            : r.choice(root["state"], "state", "estimate", {"estimate", "truth"}).value_or("estimate");
  if (overrides.seed) {
    m.seed = *overrides.seed;
  } else if (root["seed"]) {
    m.seed = static_cast<std::uint64_t>(r.number(root["seed"], "seed", 1, 0, 4294967295.0).value_or(1));
  }
  const std::map<std::string, std::string> vars{{"world", m.world.string()},
                                                {"mode", m.mode},
                                                {"state", m.state},
                                                {"seed", std::to_string(m.seed)},
                                                {"root", lookup.layout.data.string()},
                                                {"run_state", kRunStateVariable}};
  for (const auto& [k, v] : r.scalars(root["env"], "env")) {
    m.environment[k] = expand(v, vars, r, "env." + k, root["env"][k]);
  }
  m.geofence = overrides.geofence ? overrides.geofence : common::readGeofence(root["geofence"], "geofence", r);
  YAML::Node modules = root["modules"];
  if (!modules || !modules.IsMap() || modules.size() == 0) {
    r.problem("modules", modules, "expected a map of module names to modules, in start order");
  } else if (!m.hosts.empty()) {
    for (auto kv : modules) {
      readModule(kv.first.as<std::string>(), kv.second, r, lookup, vars, m);
    }
  }

  applyModuleSets(overrides.sets, r, m);

  if (YAML::Node mission = root["mission"]; mission) {
    r.onlyKeys(mission, "mission.", {"tolerance", "land", "timeout", "vehicle", "score_rate"});
    m.mission.enabled = true;
    m.mission.tolerance_m = r.number(mission["tolerance"], "mission.tolerance", 0.4, 0.01, 100.0).value_or(0.4);
    m.mission.land = r.flag(mission["land"], "mission.land", true).value_or(true);
    m.mission.timeout_s = r.number(mission["timeout"], "mission.timeout", 180.0, 1.0, 86400.0).value_or(180.0);
    m.mission.score_rate_hz =
        r.number(mission["score_rate"], "mission.score_rate", 50.0, 0.0, 1000.0).value_or(50.0);
    if (mission["vehicle"]) {
      m.mission.vehicle = r.path(r.text(mission["vehicle"], "mission.vehicle", "").value_or(""));
      if (!fs::is_regular_file(m.mission.vehicle)) {
        r.problem("mission.vehicle", mission["vehicle"], "no such file");
      }
    }
    if (m.world.empty()) {
      r.problem("mission", mission, "a mission flies to the world's goal: give 'world'");
    }
  }
  m.layout = overrides.layout ? *overrides.layout
                              : r.choice(root["layout"], "layout", "distributed", {"distributed", "composed"})
                                    .value_or("distributed");
  if (root["vehicles"]) {
    const auto hosts_of = readVehicles(root["vehicles"], r, m);
    if (overrides.vehicle && r.ok()) {
      const auto kept = std::find_if(m.vehicles.begin(), m.vehicles.end(),
                                     [&](const FleetMember& v) { return v.id == *overrides.vehicle; });
      if (kept == m.vehicles.end()) {
        r.problem("vehicles", root["vehicles"],
                  fmt::format("no vehicle {} (--vehicle): its ids are {}", *overrides.vehicle,
                              fmt::join(m.vehicleIds(), ", ")));
      } else {
        m.vehicles = {*kept};
      }
    }
    if (!m.vehicles.empty() && r.ok()) {
      expandFleet(root, r, m, hosts_of);
    }
  } else if (overrides.vehicle) {
    r.problem("vehicles", YAML::Node(std::to_string(*overrides.vehicle)),
              "--vehicle picks a vehicle of a fleet manifest; this one lists none");
  }
  if (r.ok()) {
    readContainers(root["containers"], r, lookup, m);
  }
  r.throwIfAny();
  return m;
}

ModuleSet parseModuleSet(const std::string& text, const std::string& origin)
{
  const auto colon = text.find(':');
  const auto equals = text.find('=');
  if (colon == std::string::npos || colon == 0 || equals == std::string::npos || equals < colon + 2) {
    throw common::ConfigError({origin + ": " + text + ": expected MODULE:KEY=VALUE (control:follower.max_speed=7)"});
  }
  return {text.substr(0, colon), text.substr(colon + 1, equals - colon - 1), text.substr(equals + 1)};
}

fs::path findManifest(const std::string& name_or_path, const common::Layout& layout)
{
  std::error_code ec;
  if (fs::exists(name_or_path, ec) || name_or_path.find('/') != std::string::npos) {
    return name_or_path;
  }
  const fs::path shipped =
      layout.data / "bringup" / (name_or_path.ends_with(".yaml") ? name_or_path : name_or_path + ".yaml");
  return fs::exists(shipped, ec) ? shipped : fs::path(name_or_path);
}

Manifest loadManifest(const fs::path& file, const ManifestOverrides& overrides, const ProgramLookup& lookup)
{
  const fs::path absolute = fs::absolute(file).lexically_normal();
  return parseManifest(common::readTextFile(absolute), absolute, overrides, lookup);
}

std::vector<std::string> processCommand(const Module& mod, const fs::path& state_dir)
{
  std::vector<std::string> argv{mod.program.string()};
  const auto options = [&](const Module& m) {
    if (!m.config.empty()) {
      argv.insert(argv.end(), {"--config", m.config.string()});
    }
    for (const auto& [k, v] : m.sets) {
      argv.insert(argv.end(), {"--set", k + "=" + withRunState(v, state_dir)});
    }
  };
  options(mod);
  for (const Module& hosted : mod.hosted) {
    argv.insert(argv.end(), {"--module", hosted.kind});
    options(hosted);
  }
  for (const auto& a : mod.args) {
    argv.push_back(withRunState(a, state_dir));
  }
  return argv;
}

std::string withRunState(std::string text, const std::filesystem::path& state_dir)
{
  const std::string var = kRunStateVariable;
  for (auto at = text.find(var); at != std::string::npos; at = text.find(var, at)) {
    text.replace(at, var.size(), state_dir.string());
    at += state_dir.string().size();
  }
  return text;
}

}  // namespace quad::launch
