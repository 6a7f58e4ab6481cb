// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Text placed in an XML document (an SVG picture, a DDS Security document).

#include <string>
#include <string_view>

namespace quad::common {

/// `text` with the characters XML gives a meaning (& < > ") written as their entities.
std::string xmlEscaped(std::string_view text);

}  // namespace quad::common
