// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A 64-bit digest of bytes (FNV-1a): to tell whether two pieces of data are the same, not
/// to guard them against anyone.

#include <cstddef>
#include <cstdint>
#include <span>

namespace quad::common {

/// FNV-1a's offset basis: the digest of nothing.
inline constexpr std::uint64_t kDigestStart = 14695981039346656037ULL;

/// The digest of `bytes` following on from `digest` (kDigestStart for the first).
inline std::uint64_t digest(std::span<const std::byte> bytes, std::uint64_t digest = kDigestStart)
{
  for (const std::byte b : bytes) {
    digest = (digest ^ static_cast<std::uint8_t>(b)) * 1099511628211ULL;
  }
  return digest;
}

}  // namespace quad::common
