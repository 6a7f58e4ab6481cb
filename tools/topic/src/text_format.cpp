// SPDX-License-Identifier: BSD-3-Clause
#include "quad/topic/text_format.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

namespace quad::topic {
namespace {

using Json = nlohmann::ordered_json;

bool isScalarList(const Json& v)
{
  return std::all_of(v.begin(), v.end(), [](const Json& e) { return !e.is_structured(); });
}

std::string scalarText(const Json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

void print(const Json& v, int indent, std::string& out)
{
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  for (const auto& [key, member] : v.items()) {
    out += pad + key + ":";
    if (member.is_object()) {
      out += "\n";
      print(member, indent + 2, out);
    } else if (member.is_array() && !isScalarList(member)) {
      out += "\n";
      for (const auto& element : member) {
        if (element.is_object()) {
          std::string nested;
          print(element, indent + 4, nested);
          // "- " takes the place of the first line's indentation.
          nested.replace(0, static_cast<std::size_t>(indent + 4), pad + "  - ");
          out += nested;
        } else {
          out += pad + "  - " + scalarText(element) + "\n";
        }
      }
    } else if (member.is_array()) {
      out += " [";
      for (std::size_t i = 0; i < member.size(); ++i) {
        out += (i == 0 ? "" : ", ") + scalarText(member[i]);
      }
      out += "]\n";
    } else {
      out += " " + scalarText(member) + "\n";
    }
  }
}

Json scalar(const YAML::Node& node)
{
  const std::string& s = node.Scalar();
  if (node.Tag() == "!") {  // quoted: a string whatever it looks like
    return s;
  }
  if (s == "true" || s == "false") {
    return s == "true";
  }
  std::int64_t i = 0;
  if (auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), i);
      ec == std::errc{} && p == s.data() + s.size()) {
    return i;
  }
  std::uint64_t u = 0;
  if (auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), u);
      ec == std::errc{} && p == s.data() + s.size()) {
    return u;
  }
  double d = 0.0;
  if (auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), d);
      ec == std::errc{} && p == s.data() + s.size() && std::isfinite(d)) {
    return d;
  }
  // YAML's spellings of the non-finite numbers (what bad-input tests publish).
  if (s == ".nan" || s == ".NaN" || s == ".NAN") {
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (s == ".inf" || s == ".Inf" || s == ".INF" || s == "+.inf" || s == "-.inf" || s == "-.Inf" || s == "-.INF") {
    return s[0] == '-' ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  }
  return s;
}

Json convert(const YAML::Node& node)
{
  switch (node.Type()) {
    case YAML::NodeType::Map: {
      Json out = Json::object();
      for (const auto& entry : node) {
        out[entry.first.Scalar()] = convert(entry.second);
      }
      return out;
    }
    case YAML::NodeType::Sequence: {
      Json out = Json::array();
      for (const auto& element : node) {
        out.push_back(convert(element));
      }
      return out;
    }
    case YAML::NodeType::Scalar:
      return scalar(node);
    default:
      return nullptr;
  }
}

}  // namespace

std::string toYaml(const nlohmann::ordered_json& value)
{
  std::string out;
  print(value, 0, out);
  return out;
}

nlohmann::ordered_json yamlToJson(std::string_view text)
{
  try {
    const YAML::Node root = YAML::Load(std::string(text));
    if (root.IsNull()) {
      return Json::object();
    }
    return convert(root);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument("line " + std::to_string(e.mark.line + 1) + ", column " +
                                std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
}

}  // namespace quad::topic
