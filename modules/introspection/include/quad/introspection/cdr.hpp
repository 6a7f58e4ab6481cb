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
#include <unordered_map>
#include <utility>
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
/// made of fields of one size (points, vectors, voxel changes) reading only their enums.
std::string checkBounds(const Schema& schema, std::string_view type_name, std::span<const std::uint8_t> payload);

/// checkBounds for every payload of one type: each named type it reaches is looked up in the
/// schema once, here, not by name for every sample and element (a reader checks each sample
/// it receives). check() is const and safe from several threads. Valid while `schema` lives,
/// unchanged.
class BoundsChecker {
public:
  BoundsChecker(const Schema& schema, std::string_view type_name);

  /// checkBounds(schema, type_name, payload).
  std::string check(std::span<const std::uint8_t> payload) const;

  /// What a member's type is, looked up once: a named type's definition, and for a type
  /// made of fields of one size only (primitives other than booleans, and enums), that size
  /// (0 otherwise), how many there are and which are enums, whose values must be checked.
  struct Resolved {
    const StructDef* structure = nullptr;
    const EnumDef* enumeration = nullptr;
    std::size_t uniform_size = 0;
    std::size_t fields = 0;
    std::vector<std::pair<std::size_t, std::size_t>> enum_fields;  ///< (field index, enumerators)
  };

private:
  void resolve(const Schema& schema, const TypeRef& t);

  std::string type_name_;
  const StructDef* root_;
  std::unordered_map<const TypeRef*, Resolved> resolved_;  // every type reachable from root_
};

/// The BoundsChecker of a quad message type (quadSchema()), made once for every type; null for
/// a name that is none.
const BoundsChecker* quadBoundsChecker(std::string_view type_name);

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
