// SPDX-License-Identifier: BSD-3-Clause
#include "quad/campaign/campaign_file.hpp"

#include <algorithm>

#include "quad/common/params.hpp"
#include "quad/common/yaml_input.hpp"

namespace quad::campaign {

namespace fs = std::filesystem;

CampaignFile readCampaignFile(const fs::path& file)
{
  const fs::path absolute = fs::absolute(file).lexically_normal();
  YAML::Node root = common::parseYaml(common::readTextFile(absolute), absolute.string());
  common::YamlReader r(absolute.string());
  CampaignFile c;
  if (!root.IsMap()) {
    r.problem("", root, "expected a map with worlds, axes, ... (docs/campaign.md)");
    r.throwIfAny();
  }
  r.onlyKeys(root, "", {"manifest", "worlds", "seeds", "jobs", "wall_timeout", "state", "layout", "record", "axes"});
  const auto path = [&](const YAML::Node& node, const std::string& key) -> std::optional<fs::path> {
    const auto text = r.text(node, key, std::nullopt);
    if (!text) {
      return std::nullopt;
    }
    const fs::path p = (absolute.parent_path() / *text).lexically_normal();
    if (!fs::is_regular_file(p)) {
      r.problem(key, node, "no such file (" + p.string() + ")");
      return std::nullopt;
    }
    return p;
  };
  if (root["manifest"]) {
    c.manifest = path(root["manifest"], "manifest");
  }
  if (YAML::Node worlds = root["worlds"]; worlds) {
    if (!worlds.IsSequence() || worlds.size() == 0) {
      r.problem("worlds", worlds, "expected a list of world files");
    } else {
      for (std::size_t i = 0; i < worlds.size(); ++i) {
        if (auto p = path(worlds[i], "worlds[" + std::to_string(i) + "]")) {
          c.worlds.push_back(*p);
        }
      }
    }
  }
  const auto whole = [&](const char* key, double lo, double hi) -> std::optional<int> {
    if (!root[key]) {
      return std::nullopt;
    }
    const auto v = r.number(root[key], key, std::nullopt, lo, hi);
    if (v && *v != static_cast<int>(*v)) {
      r.problem(key, root[key], "expected a whole number");
    }
    return v ? std::optional<int>(static_cast<int>(*v)) : std::nullopt;
  };
  c.seeds = whole("seeds", 1, 1000);
  c.jobs = whole("jobs", 1, 64);
  if (root["record"]) {
    c.record = r.flag(root["record"], "record", std::nullopt);
  }
  if (root["wall_timeout"]) {
    c.wall_timeout_s = r.number(root["wall_timeout"], "wall_timeout", std::nullopt, 1.0, 86400.0);
  }
  for (const auto& [key, choices] : {std::pair<const char*, std::vector<std::string>>{"state", {"estimate", "truth"}},
                                     {"layout", {"distributed", "composed"}}}) {
    if (YAML::Node node = root[key]; node) {
      const auto v = r.text(node, key, std::nullopt);
      if (v && std::find(choices.begin(), choices.end(), *v) == choices.end()) {
        r.problem(key, node, "expected " + choices[0] + " or " + choices[1]);
      } else if (v) {
        (std::string(key) == "state" ? c.state : c.layout) = *v;
      }
    }
  }
  if (YAML::Node axes = root["axes"]; axes) {
    if (!axes.IsMap()) {
      r.problem("axes", axes, "expected a map of MODULE:KEY or world:TYPE.KEY to values");
    } else {
      for (auto kv : axes) {
        const std::string key = kv.first.as<std::string>();
        const std::string where = "axes." + key;
        std::vector<std::string> values;
        if (kv.second.IsSequence() && kv.second.size() > 0) {
          for (std::size_t i = 0; i < kv.second.size(); ++i) {
            if (!kv.second[i].IsScalar()) {
              r.problem(where, kv.second, "expected a list of values, or FROM..TO");
              values.clear();
              break;
            }
            values.push_back(kv.second[i].as<std::string>());
          }
        } else if (kv.second.IsScalar()) {
          try {
            values = axisValues(kv.second.as<std::string>(), absolute.string() + ":" + where);
          } catch (const common::ConfigError&) {
            r.problem(where, kv.second, "expected a list of values, or FROM..TO (1..10)");
          }
        } else {
          r.problem(where, kv.second, "expected a list of values, or FROM..TO");
        }
        if (values.empty()) {
          continue;
        }
        try {
          Axis axis = parseAxis(key + "=" + values.front(), absolute.string() + ":" + where);
          axis.values = std::move(values);
          c.axes.push_back(std::move(axis));
        } catch (const common::ConfigError&) {
          r.problem(where, kv.second, "expected a key MODULE:KEY or world:TYPE.KEY (world:forest.density)");
        }
      }
    }
  }
  r.throwIfAny();
  return c;
}

std::string campaignFileText(const CampaignOptions& options)
{
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "manifest" << YAML::Value << options.manifest.string();
  out << YAML::Key << "worlds" << YAML::Value << YAML::BeginSeq;
  for (const fs::path& w : options.worlds) {
    out << w.string();
  }
  out << YAML::EndSeq;
  out << YAML::Key << "seeds" << YAML::Value << options.seeds;
  out << YAML::Key << "wall_timeout" << YAML::Value << options.wall_timeout_s;
  if (!options.state.empty()) {
    out << YAML::Key << "state" << YAML::Value << options.state;
  }
  if (!options.layout.empty()) {
    out << YAML::Key << "layout" << YAML::Value << options.layout;
  }
  out << YAML::Key << "record" << YAML::Value << options.record;
  out << YAML::Key << "axes" << YAML::Value << YAML::BeginMap;
  for (const Axis& a : options.axes) {
    out << YAML::Key << a.key << YAML::Value << YAML::Flow << a.values;
  }
  out << YAML::EndMap << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace quad::campaign
