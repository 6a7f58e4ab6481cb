// SPDX-License-Identifier: BSD-3-Clause
// configs/viewer/quad.layout.json, the layout Foxglove and Lichtblick import to show a
// recording: every topic it names is a quad contract, every field a plot reads is a member of
// that topic's type, and its 3D panel follows the frame the display topics are drawn in.
#include <algorithm>
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "display_node.hpp"
#include "quad/dds/topics.hpp"
#include "quad/introspection/idl.hpp"

namespace quad::display {
namespace {

nlohmann::json shippedLayout()
{
  std::ifstream in(QUAD_CONFIG_DIR "/viewer/quad.layout.json");
  EXPECT_TRUE(in) << "cannot open " QUAD_CONFIG_DIR "/viewer/quad.layout.json";
  return nlohmann::json::parse(in);
}

/// Whether `path` ("p_W.z") names a member of `type_name`, struct by struct.
bool hasField(const introspection::Schema& schema, std::string type_name, const std::string& path)
{
  std::size_t from = 0;
  while (from <= path.size()) {
    const std::size_t dot = std::min(path.find('.', from), path.size());
    const std::string name = path.substr(from, dot - from);
    const introspection::StructDef* def = schema.findStruct(type_name);
    if (def == nullptr) {
      return false;  // a member of a type without members
    }
    const auto member = std::find_if(def->members.begin(), def->members.end(),
                                      [&](const introspection::Member& m) { return m.name == name; });
    if (member == def->members.end()) {
      return false;
    }
    type_name = member->type.name;
    from = dot + 1;
  }
  return true;
}

TEST(ViewerLayout, NamesOnlyQuadTopicsAndFieldsAndFollowsTheWorldFrame)
{
  const nlohmann::json layout = shippedLayout();
  std::set<std::string> panels;
  for (const auto& [id, config] : layout.at("configById").items()) {
    const std::string kind = id.substr(0, id.find('!'));
    panels.insert(kind);
    if (kind == "3D") {
      EXPECT_EQ(config.at("followTf"), kWorldFrame);
      for (const auto& [topic, settings] : config.at("topics").items()) {
        EXPECT_TRUE(dds::topics::find(topic)) << "3D panel: topic " << topic << " is not a quad topic";
      }
      for (const auto& [frame, settings] : config.at("transforms").items()) {
        EXPECT_TRUE(frame == std::string("frame:") + kTrueBodyFrame || frame == std::string("frame:") + kBodyFrame)
            << "3D panel: " << frame;
      }
    } else if (kind == "RosOut") {
      EXPECT_EQ(config.at("topicToRender"), dds::topics::kDisplayLog.info.name);
    } else if (kind == "Plot") {
      for (const auto& series : config.at("paths")) {
        const std::string value = series.at("value");
        const std::size_t dot = value.find('.');
        const std::string topic = value.substr(0, dot);
        const auto info = dds::topics::find(topic);
        ASSERT_TRUE(info) << "Plot: topic " << topic << " is not a quad topic";
        EXPECT_TRUE(hasField(introspection::quadSchema(), std::string(info->type_name), value.substr(dot + 1)))
            << "Plot: " << value << " is not a field of " << info->type_name;
      }
    } else {
      ADD_FAILURE() << "a panel this test does not check: " << id;
    }
  }
  EXPECT_EQ(panels, (std::set<std::string>{"3D", "Plot", "RosOut"}));
}

TEST(ViewerLayout, TheFieldCheckRefusesWhatTheTypeLacks)
{
  const auto& schema = introspection::quadSchema();
  EXPECT_TRUE(hasField(schema, "quad::msg::VehicleState", "p_W.z"));
  EXPECT_FALSE(hasField(schema, "quad::msg::VehicleState", "p_W.w"));
  EXPECT_FALSE(hasField(schema, "quad::msg::VehicleState", "altitude"));
  EXPECT_FALSE(hasField(schema, "quad::msg::VehicleState", "p_W.z.more"));
}

}  // namespace
}  // namespace quad::display
