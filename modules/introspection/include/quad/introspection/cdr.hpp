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

}  // namespace quad::introspection
