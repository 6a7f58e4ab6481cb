// SPDX-License-Identifier: BSD-3-Clause
#include "quad/process/shell_quote.hpp"

namespace quad::process {

std::string shellQuote(const std::string& word)
{
  std::string out = "'";
  for (const char c : word) {
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return out + "'";
}

}  // namespace quad::process
