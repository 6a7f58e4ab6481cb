// SPDX-License-Identifier: BSD-3-Clause
#include "quad/introspection/cdr.hpp"
#include "quad/introspection/idl.hpp"

namespace quad::msg {
// Defined in the generated quad_msgs_sources.cpp: every message IDL file's text.
const std::map<std::string, std::string_view>& idlSources();
}  // namespace quad::msg

namespace quad::introspection {

const Schema& quadSchema()
{
  static const Schema schema = [] {
    Schema s;
    for (const auto& [file, text] : msg::idlSources()) {
      s.addFile(file, text);
    }
    s.link();
    return s;
  }();
  return schema;
}

const BoundsChecker* quadBoundsChecker(std::string_view type_name)
{
  static const auto checkers = [] {
    std::map<std::string, BoundsChecker, std::less<>> all;
    for (const auto& entry : quadSchema().structs()) {
      all.try_emplace(entry.first, quadSchema(), entry.first);
    }
    return all;
  }();
  const auto it = checkers.find(type_name);
  return it == checkers.end() ? nullptr : &it->second;
}

}  // namespace quad::introspection
