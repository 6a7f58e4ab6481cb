// SPDX-License-Identifier: BSD-3-Clause
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

}  // namespace quad::introspection
