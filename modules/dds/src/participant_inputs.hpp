// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// What a participant is told from outside (its environment, a manifest's options), read and
/// checked: integers in their range, IPv4 locators, the domain id's range. Private to
/// quad::dds (participant_options.cpp reads the environment, participant.cpp the options).

#include <charconv>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include <fastdds/rtps/common/Locator.h>

namespace quad::dds {

inline constexpr int kMaxDomainId = 232;  // RTPS port mapping limit with the default port parameters

/// `text` as an integer in [lo, hi]; std::invalid_argument naming `what` and the text if not.
template <class Int>
Int parseInt(std::string_view text, std::string_view what, Int lo, Int hi)
{
  Int value{};
  const auto* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc{} || ptr != end || value < lo || value > hi) {
    throw std::invalid_argument(std::string(what) + ": " + std::string(text) +
                                ": expected an integer in [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "]");
  }
  return value;
}

/// Splits "IP[:PORT]" and checks both parts; `what` names the source in errors.
eprosima::fastrtps::rtps::Locator_t parseLocator(const std::string& text, std::string_view what, bool port_required);

}  // namespace quad::dds
