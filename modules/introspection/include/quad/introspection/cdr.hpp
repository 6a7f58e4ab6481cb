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

class EncodeError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Serializes `value` (an object shaped like decodeCdr's output) as `type_name` in plain
/// little-endian CDR, encapsulation header included. Members left out are zero, false, empty
/// or the first enumerator. An unknown member, a wrong JSON type, an integer out of its
/// type's range, a string or sequence over its bound, an unknown enumerator or an array of
/// the wrong length is an EncodeError naming the field path.
std::vector<std::uint8_t> encodeCdr(const Schema& schema, std::string_view type_name,
                                    const nlohmann::ordered_json& value);

}  // namespace quad::introspection
