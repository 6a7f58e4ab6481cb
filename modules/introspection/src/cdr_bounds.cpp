// SPDX-License-Identifier: BSD-3-Clause
#include <bit>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "quad/introspection/cdr.hpp"

namespace quad::introspection {
namespace {

constexpr std::size_t kEncapsulationSize = 4;

/// Walks a payload as decodeCdr does, without building anything: checks lengths against the
/// IDL's bounds and the payload's size, enum and boolean values, and skips runs of elements whose
/// layout is fixed (a struct of primitives of one size has no padding: count * size bytes).
class BoundsWalker {
public:
  BoundsWalker(const Schema& schema, std::span<const std::uint8_t> body, bool little)
      : schema_(schema), body_(body), little_(little)
  {
  }

  void walkStruct(const StructDef& def)
  {
    for (const auto& m : def.members) {
      path_.push_back({&m.name, std::nullopt});
      walkMember(m);
      path_.pop_back();
    }
  }

private:
  struct PathPart {
    const std::string* name;
    std::optional<std::size_t> index;
  };

  [[noreturn]] void fail(const std::string& why) const
  {
    std::string path;
    for (const auto& p : path_) {
      if (p.name != nullptr) {
        path += (path.empty() ? "" : ".") + *p.name;
      }
      if (p.index) {
        path += "[" + std::to_string(*p.index) + "]";
      }
    }
    throw DecodeError(path + ": " + why + " at byte " + std::to_string(pos_ + kEncapsulationSize));
  }

  void skip(std::size_t n, std::size_t align)
  {
    pos_ = (pos_ + align - 1) / align * align;
    if (pos_ > body_.size() || body_.size() - pos_ < n) {
      fail("truncated: needs " + std::to_string(n) + " more byte(s)");
    }
    pos_ += n;
  }

  std::uint32_t length()
  {
    skip(4, 4);
    std::uint32_t v;
    std::memcpy(&v, body_.data() + pos_ - 4, 4);
    return little_ == (std::endian::native == std::endian::little) ? v : __builtin_bswap32(v);
  }

  /// The size of every primitive in `t` when they all have one size (no padding), else 0.
  std::size_t uniformSize(const TypeRef& t) const
  {
    if (t.kind == TypeRef::Kind::kPrimitive) {
      // A boolean's byte must be 0 or 1 (Fast CDR throws on anything else): checked one by one.
      return t.primitive == Primitive::kBool ? 0 : cdrSize(t.primitive);
    }
    if (t.kind != TypeRef::Kind::kNamed) {
      return 0;
    }
    if (schema_.findEnum(t.name) != nullptr) {
      return 0;  // its values must be checked one by one
    }
    const StructDef* s = schema_.findStruct(t.name);
    if (s == nullptr) {
      return 0;
    }
    std::size_t size = 0;
    for (const auto& m : s->members) {
      const std::size_t one = m.array_dims.empty() ? uniformSize(m.type) : 0;
      if (one == 0 || (size != 0 && one != size)) {
        return 0;
      }
      size = one;
    }
    return size;
  }

  std::size_t fieldsOf(const TypeRef& t) const
  {
    if (t.kind == TypeRef::Kind::kPrimitive) {
      return 1;
    }
    std::size_t n = 0;
    for (const auto& m : schema_.findStruct(t.name)->members) {
      n += fieldsOf(m.type);
    }
    return n;
  }

  void walkElements(const TypeRef& element, std::size_t count)
  {
    if (const std::size_t size = uniformSize(element); size != 0) {
      skip(count * size * fieldsOf(element), size);
      return;
    }
    for (std::size_t i = 0; i < count; ++i) {
      path_.push_back({nullptr, i});
      walkType(element);
      path_.pop_back();
    }
  }

  void walkType(const TypeRef& t)
  {
    switch (t.kind) {
      case TypeRef::Kind::kPrimitive:
        skip(cdrSize(t.primitive), cdrSize(t.primitive));
        if (t.primitive == Primitive::kBool && body_[pos_ - 1] > 1) {
          --pos_;
          fail("boolean value " + std::to_string(body_[pos_]) + " is neither 0 nor 1");
        }
        return;
      case TypeRef::Kind::kString: {
        const std::uint32_t n = length();  // with its NUL
        if (n == 0) {
          fail("string length 0 (CDR strings carry their NUL)");
        }
        if (t.bound != 0 && n - 1 > t.bound) {
          fail("string length " + std::to_string(n - 1) + " exceeds its bound " + std::to_string(t.bound));
        }
        skip(n, 1);
        return;
      }
      case TypeRef::Kind::kSequence: {
        const std::uint32_t n = length();
        if (t.bound != 0 && n > t.bound) {
          fail("sequence length " + std::to_string(n) + " exceeds its bound " + std::to_string(t.bound));
        }
        if (n > body_.size() - pos_) {
          fail("sequence length " + std::to_string(n) + " exceeds the payload");
        }
        walkElements(*t.element, n);
        return;
      }
      case TypeRef::Kind::kNamed:
        if (const StructDef* s = schema_.findStruct(t.name)) {
          walkStruct(*s);
        } else if (const EnumDef* e = schema_.findEnum(t.name)) {
          if (const std::uint32_t v = length(); v >= e->enumerators.size()) {
            fail("enum value " + std::to_string(v) + " is not an enumerator of " + t.name);
          }
        } else {
          fail("unknown type " + t.name);
        }
        return;
    }
  }

  void walkMember(const Member& m)
  {
    std::size_t count = 1;
    for (const auto d : m.array_dims) {
      count *= d;
    }
    if (m.array_dims.empty()) {
      walkType(m.type);
    } else {
      walkElements(m.type, count);
    }
  }

  const Schema& schema_;
  std::span<const std::uint8_t> body_;
  bool little_;
  std::size_t pos_ = 0;
  std::vector<PathPart> path_;
};

}  // namespace

std::string checkBounds(const Schema& schema, std::string_view type_name, std::span<const std::uint8_t> payload)
{
  const StructDef* def = schema.findStruct(type_name);
  if (def == nullptr) {
    return "no IDL struct named '" + std::string(type_name) + "'";
  }
  if (payload.size() < kEncapsulationSize || payload[0] != 0 || payload[1] > 1) {
    return "not a plain CDR payload";
  }
  try {
    BoundsWalker(schema, payload.subspan(kEncapsulationSize), payload[1] == 1).walkStruct(*def);
  } catch (const DecodeError& e) {
    return e.what();
  }
  return "";
}

}  // namespace quad::introspection
