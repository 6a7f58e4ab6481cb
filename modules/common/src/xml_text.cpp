// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/xml_text.hpp"

namespace quad::common {

std::string xmlEscaped(std::string_view text)
{
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace quad::common
