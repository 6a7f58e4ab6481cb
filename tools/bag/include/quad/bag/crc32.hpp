// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// CRC-32 (ISO-HDLC: reflected polynomial 0xEDB88320, as zlib and MCAP use it).

#include <cstddef>
#include <cstdint>

namespace quad::bag {

/// The CRC of `size` bytes at `data`, continued from `crc` (0 to start). On x86-64 CPUs with
/// PCLMULQDQ, runs of 64 bytes and more are folded with carry-less multiplication; everything
/// else goes eight bytes a step through tables.
std::uint32_t crc32(const void* data, std::size_t size, std::uint32_t crc = 0);

/// The table-driven CRC alone, whatever the CPU (what crc32 falls back to; for tests).
std::uint32_t crc32Tables(const void* data, std::size_t size, std::uint32_t crc = 0);

}  // namespace quad::bag
