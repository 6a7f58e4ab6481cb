// SPDX-License-Identifier: BSD-3-Clause
#include "quad/introspection/cdr.hpp"

#include <bit>
#include <cstring>
#include <string>

namespace quad::introspection {
namespace {

constexpr std::size_t kEncapsulationSize = 4;

class Reader {
public:
  Reader(const Schema& schema, std::span<const std::uint8_t> body, bool little_endian,
         const DecodeOptions& options)
      : schema_(schema), body_(body), little_(little_endian), options_(options)
  {
  }

  nlohmann::ordered_json readStruct(const StructDef& def, const std::string& path)
  {
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    for (const auto& m : def.members) {
      const std::string member_path = path.empty() ? m.name : path + "." + m.name;
      out[m.name] = readMember(m, member_path);
    }
    return out;
  }

  std::size_t offset() const { return pos_; }

private:
  [[noreturn]] void fail(const std::string& path, const std::string& why) const
  {
    throw DecodeError(path + ": " + why + " at byte " + std::to_string(pos_ + kEncapsulationSize));
  }

  void align(std::size_t n)
  {
    pos_ = (pos_ + n - 1) / n * n;  // CDR aligns relative to the end of the encapsulation
  }

  const std::uint8_t* take(std::size_t n, const std::string& path)
  {
    if (pos_ > body_.size() || body_.size() - pos_ < n) {
      fail(path, "truncated: needs " + std::to_string(n) + " more byte(s)");
    }
    const std::uint8_t* p = body_.data() + pos_;
    pos_ += n;
    return p;
  }

  template <class T>
  T scalar(const std::string& path)
  {
    align(sizeof(T));
    const std::uint8_t* p = take(sizeof(T), path);
    std::uint8_t bytes[sizeof(T)];
    std::memcpy(bytes, p, sizeof(T));
    if (little_ != (std::endian::native == std::endian::little)) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) {
        std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
      }
    }
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  }

  nlohmann::ordered_json readPrimitive(Primitive p, const std::string& path)
  {
    switch (p) {
      case Primitive::kBool: {
        const auto v = scalar<std::uint8_t>(path);
        if (v > 1) {
          fail(path, "boolean byte " + std::to_string(v) + " is neither 0 nor 1");
        }
        return v == 1;
      }
      case Primitive::kOctet:
        return scalar<std::uint8_t>(path);
      case Primitive::kChar:
        return std::string(1, static_cast<char>(scalar<std::uint8_t>(path)));
      case Primitive::kInt16:
        return scalar<std::int16_t>(path);
      case Primitive::kUInt16:
        return scalar<std::uint16_t>(path);
      case Primitive::kInt32:
        return scalar<std::int32_t>(path);
      case Primitive::kUInt32:
        return scalar<std::uint32_t>(path);
      case Primitive::kInt64:
        return scalar<std::int64_t>(path);
      case Primitive::kUInt64:
        return scalar<std::uint64_t>(path);
      case Primitive::kFloat:
        return scalar<float>(path);
      case Primitive::kDouble:
        return scalar<double>(path);
    }
    return nullptr;
  }

  std::string readString(const TypeRef& t, const std::string& path)
  {
    const auto length = scalar<std::uint32_t>(path);  // includes the terminating NUL
    if (length == 0) {
      fail(path, "string length 0 (CDR strings carry their NUL)");
    }
    if (t.bound != 0 && length - 1 > t.bound) {
      fail(path, "string length " + std::to_string(length - 1) + " exceeds its bound " +
                     std::to_string(t.bound));
    }
    const std::uint8_t* p = take(length, path);
    if (p[length - 1] != 0) {
      fail(path, "string is not NUL-terminated");
    }
    return std::string(reinterpret_cast<const char*>(p), length - 1);
  }

  /// Reads `count` elements of `element` into a list, keeping at most max_elements.
  nlohmann::ordered_json readList(std::size_t count, const std::function<nlohmann::ordered_json(
                                                         const std::string&)>& element,
                                  const std::string& path)
  {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < count; ++i) {
      auto value = element(path + "[" + std::to_string(i) + "]");
      if (i < options_.max_elements) {
        out.push_back(std::move(value));
      }
    }
    if (count > options_.max_elements) {
      out.push_back("... " + std::to_string(count - options_.max_elements) + " more");
    }
    return out;
  }

  nlohmann::ordered_json readType(const TypeRef& t, const std::string& path)
  {
    switch (t.kind) {
      case TypeRef::Kind::kPrimitive:
        return readPrimitive(t.primitive, path);
      case TypeRef::Kind::kString:
        return readString(t, path);
      case TypeRef::Kind::kSequence: {
        const auto count = scalar<std::uint32_t>(path);
        if (t.bound != 0 && count > t.bound) {
          fail(path, "sequence length " + std::to_string(count) + " exceeds its bound " +
                         std::to_string(t.bound));
        }
        if (count > body_.size() - std::min(pos_, body_.size())) {
          // Every element takes at least one byte: refuse before looping over garbage.
          fail(path, "sequence length " + std::to_string(count) + " exceeds the payload");
        }
        return readList(count, [&](const std::string& p) { return readType(*t.element, p); },
                        path);
      }
      case TypeRef::Kind::kNamed:
        return readNamed(t.name, path);
    }
    return nullptr;
  }

  nlohmann::ordered_json readNamed(const std::string& name, const std::string& path)
  {
    if (const StructDef* s = schema_.findStruct(name)) {
      return readStruct(*s, path);
    }
    if (const EnumDef* e = schema_.findEnum(name)) {
      const auto v = scalar<std::uint32_t>(path);
      if (v >= e->enumerators.size()) {
        fail(path, "enum value " + std::to_string(v) + " is not an enumerator of " + name);
      }
      return e->enumerators[v];
    }
    fail(path, "unknown type " + name);
  }

  nlohmann::ordered_json readMember(const Member& m, const std::string& path)
  {
    if (m.array_dims.empty()) {
      return readType(m.type, path);
    }
    return readArray(m, 0, path);
  }

  nlohmann::ordered_json readArray(const Member& m, std::size_t dim, const std::string& path)
  {
    return readList(m.array_dims[dim],
                    [&](const std::string& p) {
                      return dim + 1 < m.array_dims.size() ? readArray(m, dim + 1, p)
                                                           : readType(m.type, p);
                    },
                    path);
  }

  const Schema& schema_;
  std::span<const std::uint8_t> body_;
  bool little_;
  const DecodeOptions& options_;
  std::size_t pos_ = 0;
};

}  // namespace

nlohmann::ordered_json decodeCdr(const Schema& schema, std::string_view type_name,
                                 std::span<const std::uint8_t> payload,
                                 const DecodeOptions& options)
{
  const StructDef* def = schema.findStruct(type_name);
  if (def == nullptr) {
    throw DecodeError("no IDL struct named '" + std::string(type_name) + "'");
  }
  if (payload.size() < kEncapsulationSize) {
    throw DecodeError("payload of " + std::to_string(payload.size()) +
                      " bytes is shorter than its encapsulation header");
  }
  // Encapsulation identifiers (DDS-XTypes 7.6.3.1.2): 0x0000 CDR_BE, 0x0001 CDR_LE.
  if (payload[0] != 0 || payload[1] > 1) {
    throw DecodeError("unsupported encapsulation 0x" + std::to_string(payload[0]) + "/" +
                      std::to_string(payload[1]) + " (only plain CDR is decoded)");
  }
  Reader reader(schema, payload.subspan(kEncapsulationSize), payload[1] == 1, options);
  return reader.readStruct(*def, "");
}

}  // namespace quad::introspection
