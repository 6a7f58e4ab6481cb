// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// How often a piece of text occurs in another (elements of a drawn SVG, lines of a report).

#include <string>

namespace quad::test {

/// Non-overlapping occurrences of `what` in `text`.
inline int occurrences(const std::string& text, const std::string& what)
{
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) {
    ++n;
  }
  return n;
}

}  // namespace quad::test
