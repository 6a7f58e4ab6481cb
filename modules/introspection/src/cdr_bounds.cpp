// SPDX-License-Identifier: BSD-3-Clause
#include <bit>
#include <cstring>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "quad/introspection/cdr.hpp"

namespace quad::introspection {
namespace {

constexpr std::size_t kEncapsulationSize = 4;
constexpr std::size_t kEnumSize = 4;  // an enum's value is an unsigned long in CDR

/// Walks a payload as decodeCdr does, without building anything: checks lengths against the
/// IDL's bounds and the payload's size, enum and boolean values, and skips runs of elements whose
/// layout is fixed (a struct of fields of one size has no padding: count * size bytes), reading
/// only their enums' values in place.
/// With kNamesFields, a fault is a DecodeError naming the member's path; without, which is
/// faster (nothing kept per member and element), it is a Refused, and the payload is walked
/// again with the path to say where.
struct Refused {};

template <bool kNamesFields>
class BoundsWalker {
public:
  using Resolved = BoundsChecker::Resolved;

  BoundsWalker(const std::unordered_map<const TypeRef*, Resolved>& resolved, std::span<const std::uint8_t> body,
               bool little)
      : resolved_(resolved), body_(body), little_(little)
  {
  }

  void walkStruct(const StructDef& def)
  {
    for (const auto& m : def.members) {
      if constexpr (kNamesFields) {
        path_.push_back({&m.name, std::nullopt});
      }
      walkMember(m);
      if constexpr (kNamesFields) {
        path_.pop_back();
      }
    }
  }

private:
  struct PathPart {
    const std::string* name;
    std::optional<std::size_t> index;
  };

  template <class Why>
  [[noreturn]] void fail(Why&& why) const
  {
    if constexpr (!kNamesFields) {
      throw Refused{};
    }
    std::string path;
    for (const auto& p : path_) {
      if (p.name != nullptr) {
        path += (path.empty() ? "" : ".") + *p.name;
      }
      if (p.index) {
        path += "[" + std::to_string(*p.index) + "]";
      }
    }
    throw DecodeError(path + ": " + why() + " at byte " + std::to_string(pos_ + kEncapsulationSize));
  }

  void skip(std::size_t n, std::size_t align)
  {
    pos_ = (pos_ + align - 1) / align * align;
    if (pos_ > body_.size() || body_.size() - pos_ < n) {
      fail([&] { return "truncated: needs " + std::to_string(n) + " more byte(s)"; });
    }
    pos_ += n;
  }

  std::uint32_t length()
  {
    skip(4, 4);
    return word(pos_ - 4);
  }

  /// The 4-byte unsigned value at `at`, which must be within the payload.
  std::uint32_t word(std::size_t at) const
  {
    std::uint32_t v;
    std::memcpy(&v, body_.data() + at, 4);
    return little_ == (std::endian::native == std::endian::little) ? v : __builtin_bswap32(v);
  }

  const Resolved& resolved(const TypeRef& t) const { return resolved_.at(&t); }

  void walkElements(const TypeRef& element, std::size_t count)
  {
    // A run of fixed layout is skipped whole, its enums' values read in place; a fault in one
    // is found again element by element by the walk that names the field. No elements: no
    // padding either (Fast CDR aligns an element as it writes it).
    if (count == 0) {
      return;
    }
    if (const Resolved& r = resolved(element); r.uniform_size != 0 && (!kNamesFields || r.enum_fields.empty())) {
      skip(count * r.uniform_size * r.fields, r.uniform_size);
      const std::size_t start = pos_ - count * r.uniform_size * r.fields;
      for (std::size_t i = 0; i < count && !r.enum_fields.empty(); ++i) {
        for (const auto& [index, enumerators] : r.enum_fields) {
          if (word(start + (i * r.fields + index) * kEnumSize) >= enumerators) {
            throw Refused{};
          }
        }
      }
      return;
    }
    for (std::size_t i = 0; i < count; ++i) {
      if constexpr (kNamesFields) {
        path_.push_back({nullptr, i});
      }
      walkType(element);
      if constexpr (kNamesFields) {
        path_.pop_back();
      }
    }
  }

  void walkType(const TypeRef& t)
  {
    switch (t.kind) {
      case TypeRef::Kind::kPrimitive:
        skip(cdrSize(t.primitive), cdrSize(t.primitive));
        if (t.primitive == Primitive::kBool && body_[pos_ - 1] > 1) {
          --pos_;
          fail([&] { return "boolean value " + std::to_string(body_[pos_]) + " is neither 0 nor 1"; });
        }
        return;
      case TypeRef::Kind::kString: {
        const std::uint32_t n = length();  // with its NUL
        if (n == 0) {
          fail([&] { return "string length 0 (CDR strings carry their NUL)"; });
        }
        if (t.bound != 0 && n - 1 > t.bound) {
          fail([&] { return "string length " + std::to_string(n - 1) + " exceeds its bound " + std::to_string(t.bound); });
        }
        skip(n, 1);
        return;
      }
      case TypeRef::Kind::kSequence: {
        const std::uint32_t n = length();
        if (t.bound != 0 && n > t.bound) {
          fail([&] { return "sequence length " + std::to_string(n) + " exceeds its bound " + std::to_string(t.bound); });
        }
        if (n > body_.size() - pos_) {
          fail([&] { return "sequence length " + std::to_string(n) + " exceeds the payload"; });
        }
        walkElements(*t.element, n);
        return;
      }
      case TypeRef::Kind::kNamed:
        if (const Resolved& r = resolved(t); r.structure != nullptr) {
          walkStruct(*r.structure);
        } else if (const EnumDef* e = r.enumeration) {
          if (const std::uint32_t v = length(); v >= e->enumerators.size()) {
            fail([&] { return "enum value " + std::to_string(v) + " is not an enumerator of " + t.name; });
          }
        } else {
          fail([&] { return "unknown type " + t.name; });
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

  const std::unordered_map<const TypeRef*, Resolved>& resolved_;
  std::span<const std::uint8_t> body_;
  bool little_;
  std::size_t pos_ = 0;
  std::vector<PathPart> path_;
};

}  // namespace

BoundsChecker::BoundsChecker(const Schema& schema, std::string_view type_name)
    : type_name_(type_name), root_(schema.findStruct(type_name))
{
  if (root_ != nullptr) {
    for (const auto& m : root_->members) {
      resolve(schema, m.type);
    }
  }
}

void BoundsChecker::resolve(const Schema& schema, const TypeRef& t)
{
  if (resolved_.contains(&t)) {
    return;  // seen, or being resolved (a struct reached again through a sequence of itself)
  }
  Resolved& r = resolved_[&t];  // stays where it is as the map grows (a node of it)
  switch (t.kind) {
    case TypeRef::Kind::kPrimitive:
      // A boolean's byte must be 0 or 1 (Fast CDR throws on anything else): checked one by one.
      r.uniform_size = t.primitive == Primitive::kBool ? 0 : cdrSize(t.primitive);
      r.fields = 1;
      return;
    case TypeRef::Kind::kString:
      return;
    case TypeRef::Kind::kSequence:
      resolve(schema, *t.element);
      return;
    case TypeRef::Kind::kNamed:
      break;
  }
  const StructDef* s = schema.findStruct(t.name);
  const EnumDef* e = s == nullptr ? schema.findEnum(t.name) : nullptr;
  std::size_t size = e != nullptr ? kEnumSize : 0;
  std::size_t fields = e != nullptr ? 1 : 0;
  std::vector<std::pair<std::size_t, std::size_t>> enum_fields;
  if (e != nullptr) {
    enum_fields.emplace_back(0, e->enumerators.size());
  }
  bool uniform = s != nullptr || e != nullptr;
  if (s != nullptr) {
    for (const auto& m : s->members) {
      resolve(schema, m.type);
      const Resolved& member = resolved_.at(&m.type);
      for (const auto& [index, enumerators] : member.enum_fields) {
        enum_fields.emplace_back(fields + index, enumerators);
      }
      fields += member.fields;
      if (!m.array_dims.empty() || member.uniform_size == 0 || (size != 0 && member.uniform_size != size)) {
        uniform = false;
      }
      size = member.uniform_size;
    }
  }
  r.structure = s;
  r.enumeration = e;
  r.uniform_size = uniform ? size : 0;
  r.fields = fields;
  if (uniform) {
    r.enum_fields = std::move(enum_fields);
  }
}

std::string BoundsChecker::check(std::span<const std::uint8_t> payload) const
{
  if (root_ == nullptr) {
    return "no IDL struct named '" + type_name_ + "'";
  }
  if (payload.size() < kEncapsulationSize || payload[0] != 0 || payload[1] > 1) {
    return "not a plain CDR payload";
  }
  const auto body = payload.subspan(kEncapsulationSize);
  try {
    BoundsWalker<false>(resolved_, body, payload[1] == 1).walkStruct(*root_);
    return "";
  } catch (const Refused&) {
  }
  try {
    BoundsWalker<true>(resolved_, body, payload[1] == 1).walkStruct(*root_);
  } catch (const DecodeError& e) {
    return e.what();
  }
  return "refused, at a place the second walk did not find";  // not reached: the walks are one
}

std::string checkBounds(const Schema& schema, std::string_view type_name, std::span<const std::uint8_t> payload)
{
  return BoundsChecker(schema, type_name).check(payload);
}

}  // namespace quad::introspection
