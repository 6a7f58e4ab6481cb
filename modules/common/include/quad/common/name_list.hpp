// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A comma-separated list of names as parameters and command lines give it ("plant, control").

#include <string>
#include <string_view>
#include <vector>

namespace quad::common {

/// The names in `text`, in order: split at commas, blanks around each dropped, empty ones
/// skipped.
std::vector<std::string> nameList(std::string_view text);

}  // namespace quad::common
