// SPDX-License-Identifier: BSD-3-Clause
// The digest: FNV-1a's published values, one byte's difference seen, pieces chained as the whole.
#include "quad/common/digest.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string_view>

namespace quad::common {
namespace {

std::span<const std::byte> bytesOf(std::string_view s) { return std::as_bytes(std::span(s.data(), s.size())); }

TEST(Digest, IsFnv1aAndChainsPiecesAsTheWhole)
{
  EXPECT_EQ(digest({}), kDigestStart);
  EXPECT_EQ(digest(bytesOf("a")), 0xaf63dc4c8601ec8cULL);  // FNV-1a 64 of "a", as published
  EXPECT_EQ(digest(bytesOf("foobar")), 0x85944171f73967e8ULL);
  EXPECT_EQ(digest(bytesOf("bar"), digest(bytesOf("foo"))), digest(bytesOf("foobar")));
  const std::array<float, 3> a{1.0F, 2.0F, 3.0F};
  std::array<float, 3> b = a;
  EXPECT_EQ(digest(std::as_bytes(std::span(a))), digest(std::as_bytes(std::span(b))));
  b[2] = std::nextafter(3.0F, 4.0F);
  EXPECT_NE(digest(std::as_bytes(std::span(a))), digest(std::as_bytes(std::span(b))));
}

}  // namespace
}  // namespace quad::common
