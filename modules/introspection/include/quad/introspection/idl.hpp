// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A model of the IDL subset quad's messages use, parsed from the IDL text itself, so that
/// tools decode any topic's samples (and recordings carry their schema) from one source of
/// truth: the .idl files.
///
/// Supported: modules, structs, enums, members of the primitive types, bounded and unbounded
/// string<N> and sequence<T, N>, fixed arrays T name[N], annotations (kept by name). Anything
/// else is an IdlError that names the file, line and token.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace quad::introspection {

class IdlError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

enum class Primitive {
  kBool, kOctet, kChar, kInt16, kUInt16, kInt32, kUInt32, kInt64, kUInt64, kFloat, kDouble,
};

/// Size in bytes of a primitive in CDR (also its alignment).
std::size_t cdrSize(Primitive p);

/// A member's type: a primitive, a string, a sequence of an element type, or a named
/// struct/enum (resolved through the Schema).
struct TypeRef {
  enum class Kind { kPrimitive, kString, kSequence, kNamed };
  Kind kind = Kind::kPrimitive;
  Primitive primitive = Primitive::kInt32;
  std::uint32_t bound = 0;               ///< string or sequence bound; 0 = unbounded
  std::shared_ptr<TypeRef> element;      ///< sequence element
  std::string name;   ///< kNamed: as written, fully scoped ("quad::msg::Header") after link()
  std::string scope;  ///< kNamed: the module scope it was written in ("quad::msg")
};

struct Member {
  std::string name;
  TypeRef type;
  std::vector<std::uint32_t> array_dims;  ///< T name[3][4] -> {3, 4}; empty if not an array
  std::vector<std::string> annotations;   ///< "key", ...
};

struct StructDef {
  std::string name;  ///< fully scoped
  std::vector<Member> members;
  std::string file;  ///< the IDL file it came from
};

struct EnumDef {
  std::string name;  ///< fully scoped
  std::vector<std::string> enumerators;
  std::string file;
};

/// Every type parsed from a set of IDL files.
class Schema {
public:
  /// Parses one file's text and adds its definitions. Files may come in any order: call
  /// link() once all are added.
  void addFile(std::string_view file_name, std::string_view text);

  const StructDef* findStruct(std::string_view scoped_name) const;
  const EnumDef* findEnum(std::string_view scoped_name) const;
  /// The name of an enum's value ("CONTROL_HOVER"), or "<enum> <value>" when the enum or the
  /// value is not defined.
  std::string enumeratorName(std::string_view enum_name, std::int64_t value) const;

  /// Resolves a name used inside `scope` ("Header" inside quad::msg -> quad::msg::Header) by
  /// the IDL rule: innermost enclosing scope first. Nothing if no definition matches.
  std::optional<std::string> resolve(std::string_view name, std::string_view scope) const;

  /// The IDL text of `type_name` and every type it depends on, dependencies first, in one
  /// self-contained document without #include (what an MCAP omgidl schema must hold).
  /// Needs link().
  std::string flattenedIdl(std::string_view type_name) const;

  /// Resolves every named member type to its fully scoped definition; throws IdlError naming
  /// the file, struct, member and type when one is not defined.
  void link();

  const std::map<std::string, StructDef, std::less<>>& structs() const { return structs_; }

private:
  friend class Parser;
  std::map<std::string, StructDef, std::less<>> structs_;
  std::map<std::string, EnumDef, std::less<>> enums_;
  std::map<std::string, std::string, std::less<>> file_text_;
  std::map<std::string, std::string, std::less<>> definition_text_;  // per scoped name
};

/// The schema of every quad message, from the IDL embedded at build time.
const Schema& quadSchema();

}  // namespace quad::introspection
