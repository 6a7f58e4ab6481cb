// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/name_list.hpp"

#include <algorithm>

namespace quad::common {

std::vector<std::string> nameList(std::string_view text)
{
  std::vector<std::string> names;
  while (!text.empty()) {
    const std::size_t comma = text.find(',');
    std::string_view item = text.substr(0, comma);
    text = comma == std::string_view::npos ? std::string_view() : text.substr(comma + 1);
    item.remove_prefix(std::min(item.size(), item.find_first_not_of(' ')));
    item = item.substr(0, item.find_last_not_of(' ') + 1);
    if (!item.empty()) {
      names.emplace_back(item);
    }
  }
  return names;
}

}  // namespace quad::common
