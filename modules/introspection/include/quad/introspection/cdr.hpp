// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Decoding of serialized samples (plain CDR, XCDR1, as Fast CDR 1 writes them) driven by the
/// IDL schema: any topic can be printed or checked without its generated C++ type.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "quad/introspection/idl.hpp"

namespace quad::introspection {

class DecodeError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct DecodeOptions {
  /// Longer sequences and arrays keep their first elements and end with a "... N more" string.
  std::size_t max_elements = std::numeric_limits<std::size_t>::max();
};

/// Decodes `payload` (starting with its 4-byte encapsulation header) as `type_name`.
/// Structs become objects (members in order), enums their enumerator names, sequences and
/// arrays lists. Malformed input (truncated, a bound exceeded, an enum value out of range, an
/// unsupported encapsulation) is a DecodeError naming the field path and the byte offset.
nlohmann::ordered_json decodeCdr(const Schema& schema, std::string_view type_name,
                                 std::span<const std::uint8_t> payload,
                                 const DecodeOptions& options = {});

/// What is wrong with `payload` as `type_name` against its IDL: a string or sequence longer
/// than its bound or than the payload, an enum value that is no enumerator, a truncated
/// member ("waypoints_W: sequence length 5000 exceeds its bound 4096 at byte 40"); "" when
/// nothing is. Much cheaper than decodeCdr: it builds nothing, and skips runs of elements
/// made of primitives of one size (points, vectors, voxel indices) without reading them.
std::string checkBounds(const Schema& schema, std::string_view type_name, std::span<const std::uint8_t> payload);

class EncodeError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Serializes `value` (an object shaped like decodeCdr's output) as `type_name` in plain
/// little-endian CDR, encapsulation header included. Members left out are zero, false, empty
/// or the first enumerator. An unknown member, a wrong JSON type, an integer out of its
/// type's range, a string or sequence over its bound (unless EncodeOptions say otherwise), an
/// unknown enumerator or an array of the wrong length is an EncodeError naming the field path.
struct EncodeOptions {
  /// false: strings and sequences longer than their bound are written as given (a payload
  /// that breaks its IDL, for fault injection); true: they are an EncodeError.
  bool enforce_bounds = true;
};

std::vector<std::uint8_t> encodeCdr(const Schema& schema, std::string_view type_name,
                                    const nlohmann::ordered_json& value, const EncodeOptions& options = {});

}  // namespace quad::introspection
