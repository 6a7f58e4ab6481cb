// SPDX-License-Identifier: BSD-3-Clause
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "quad/introspection/cdr.hpp"

namespace quad::introspection {
namespace {

using Json = nlohmann::ordered_json;
constexpr std::size_t kEncapsulationSize = 4;

class Writer {
public:
  /// Starts the payload with its encapsulation header: CDR_LE, no options.
  Writer(const Schema& schema, const EncodeOptions& options)
      : schema_(schema), options_(options), body_{0x00, 0x01, 0x00, 0x00}
  {
  }

  void writeStruct(const StructDef& def, const Json* value, const std::string& path)
  {
    if (value != nullptr && !value->is_object()) {
      fail(path.empty() ? def.name : path, "expected an object for " + def.name);
    }
    if (value != nullptr) {
      for (const auto& item : value->items()) {
        const std::string& key = item.key();
        const bool known = std::any_of(def.members.begin(), def.members.end(),
                                       [&key](const Member& m) { return m.name == key; });
        if (!known) {
          std::string fields;
          for (const auto& m : def.members) {
            fields += (fields.empty() ? "" : ", ") + m.name;
          }
          fail(join(path, key), "unknown field of " + def.name + " (fields: " + fields + ")");
        }
      }
    }
    for (const auto& m : def.members) {
      const Json* member = (value != nullptr && value->contains(m.name)) ? &(*value)[m.name] : nullptr;
      writeMember(m, member, join(path, m.name));
    }
  }

  std::vector<std::uint8_t> take() { return std::move(body_); }

private:
  static std::string join(const std::string& path, const std::string& name)
  {
    return path.empty() ? name : path + "." + name;
  }

  [[noreturn]] static void fail(const std::string& path, const std::string& why)
  {
    throw EncodeError(path + ": " + why);
  }

  /// CDR aligns relative to the end of the encapsulation header.
  void align(std::size_t n)
  {
    const std::size_t offset = body_.size() - kEncapsulationSize;
    body_.resize(kEncapsulationSize + (offset + n - 1) / n * n, 0);
  }

  template <class T>
  void put(T v)
  {
    align(sizeof(T));
    const std::size_t at = body_.size();
    body_.resize(at + sizeof(T));
    std::memcpy(body_.data() + at, &v, sizeof(T));  // little-endian hosts only (checked below)
  }

  template <class T>
  T integer(const Json* v, const std::string& path)
  {
    if (v == nullptr) {
      return T{0};
    }
    if (!v->is_number_integer()) {
      fail(path, "expected an integer, got " + v->dump());
    }
    if (v->is_number_unsigned()) {
      const auto u = v->get<std::uint64_t>();
      if (u > static_cast<std::uint64_t>(std::numeric_limits<T>::max())) {
        fail(path, v->dump() + " is out of range");
      }
      return static_cast<T>(u);
    }
    const auto i = v->get<std::int64_t>();
    if constexpr (std::is_unsigned_v<T>) {
      if (i < 0) {
        fail(path, v->dump() + " is negative");
      }
      if (static_cast<std::uint64_t>(i) > static_cast<std::uint64_t>(std::numeric_limits<T>::max())) {
        fail(path, v->dump() + " is out of range");
      }
    } else if (i < std::numeric_limits<T>::min() || i > std::numeric_limits<T>::max()) {
      fail(path, v->dump() + " is out of range");
    }
    return static_cast<T>(i);
  }

  double real(const Json* v, const std::string& path)
  {
    if (v == nullptr) {
      return 0.0;
    }
    if (!v->is_number()) {
      fail(path, "expected a number, got " + v->dump());
    }
    return v->get<double>();
  }

  void writePrimitive(Primitive p, const Json* v, const std::string& path)
  {
    switch (p) {
      case Primitive::kBool:
        if (v != nullptr && !v->is_boolean()) {
          fail(path, "expected true or false, got " + v->dump());
        }
        put<std::uint8_t>(v != nullptr && v->get<bool>() ? 1 : 0);
        return;
      case Primitive::kOctet:
        put(integer<std::uint8_t>(v, path));
        return;
      case Primitive::kChar: {
        if (v != nullptr && (!v->is_string() || v->get<std::string>().size() != 1)) {
          fail(path, "expected a one-character string, got " + v->dump());
        }
        put<std::uint8_t>(v == nullptr ? 0 : static_cast<std::uint8_t>(v->get<std::string>()[0]));
        return;
      }
      case Primitive::kInt16:
        put(integer<std::int16_t>(v, path));
        return;
      case Primitive::kUInt16:
        put(integer<std::uint16_t>(v, path));
        return;
      case Primitive::kInt32:
        put(integer<std::int32_t>(v, path));
        return;
      case Primitive::kUInt32:
        put(integer<std::uint32_t>(v, path));
        return;
      case Primitive::kInt64:
        put(integer<std::int64_t>(v, path));
        return;
      case Primitive::kUInt64:
        put(integer<std::uint64_t>(v, path));
        return;
      case Primitive::kFloat:
        put(static_cast<float>(real(v, path)));
        return;
      case Primitive::kDouble:
        put(real(v, path));
        return;
    }
  }

  void writeType(const TypeRef& t, const Json* v, const std::string& path)
  {
    switch (t.kind) {
      case TypeRef::Kind::kPrimitive:
        writePrimitive(t.primitive, v, path);
        return;
      case TypeRef::Kind::kString: {
        if (v != nullptr && !v->is_string()) {
          fail(path, "expected a string, got " + v->dump());
        }
        const std::string s = v == nullptr ? "" : v->get<std::string>();
        if (options_.enforce_bounds && t.bound != 0 && s.size() > t.bound) {
          fail(path, "string of " + std::to_string(s.size()) + " characters exceeds its bound " +
                         std::to_string(t.bound));
        }
        put(static_cast<std::uint32_t>(s.size() + 1));
        const std::size_t at = body_.size();
        body_.resize(at + s.size() + 1, 0);
        std::memcpy(body_.data() + at, s.data(), s.size());
        return;
      }
      case TypeRef::Kind::kSequence: {
        if (v != nullptr && !v->is_array()) {
          fail(path, "expected a list, got " + v->dump());
        }
        const std::size_t n = v == nullptr ? 0 : v->size();
        if (options_.enforce_bounds && t.bound != 0 && n > t.bound) {
          fail(path, "list of " + std::to_string(n) + " exceeds its bound " + std::to_string(t.bound));
        }
        put(static_cast<std::uint32_t>(n));
        for (std::size_t i = 0; i < n; ++i) {
          writeType(*t.element, &(*v)[i], path + "[" + std::to_string(i) + "]");
        }
        return;
      }
      case TypeRef::Kind::kNamed:
        writeNamed(t.name, v, path);
        return;
    }
  }

  void writeNamed(const std::string& name, const Json* v, const std::string& path)
  {
    if (const StructDef* s = schema_.findStruct(name)) {
      writeStruct(*s, v, path);
      return;
    }
    const EnumDef* e = schema_.findEnum(name);
    if (e == nullptr) {
      fail(path, "unknown type " + name);
    }
    std::uint32_t index = 0;
    if (v != nullptr && v->is_string()) {
      const auto it = std::find(e->enumerators.begin(), e->enumerators.end(), v->get<std::string>());
      if (it == e->enumerators.end()) {
        std::string names;
        for (const auto& n : e->enumerators) {
          names += (names.empty() ? "" : ", ") + n;
        }
        fail(path, v->dump() + " is not one of " + names);
      }
      index = static_cast<std::uint32_t>(it - e->enumerators.begin());
    } else if (v != nullptr) {
      index = integer<std::uint32_t>(v, path);
      if (index >= e->enumerators.size()) {
        fail(path, std::to_string(index) + " is not an enumerator of " + name);
      }
    }
    put(index);
  }

  void writeMember(const Member& m, const Json* v, const std::string& path)
  {
    if (m.array_dims.empty()) {
      writeType(m.type, v, path);
    } else {
      writeArray(m, 0, v, path);
    }
  }

  void writeArray(const Member& m, std::size_t dim, const Json* v, const std::string& path)
  {
    const std::size_t n = m.array_dims[dim];
    if (v != nullptr && (!v->is_array() || v->size() != n)) {
      fail(path, "expected a list of " + std::to_string(n) + ", got " + v->dump());
    }
    for (std::size_t i = 0; i < n; ++i) {
      const Json* element = v == nullptr ? nullptr : &(*v)[i];
      const std::string p = path + "[" + std::to_string(i) + "]";
      if (dim + 1 < m.array_dims.size()) {
        writeArray(m, dim + 1, element, p);
      } else {
        writeType(m.type, element, p);
      }
    }
  }

  const Schema& schema_;
  const EncodeOptions& options_;
  std::vector<std::uint8_t> body_;
};

static_assert(std::endian::native == std::endian::little, "encodeCdr writes CDR_LE natively");

}  // namespace

std::vector<std::uint8_t> encodeCdr(const Schema& schema, std::string_view type_name,
                                    const nlohmann::ordered_json& value, const EncodeOptions& options)
{
  const StructDef* def = schema.findStruct(type_name);
  if (def == nullptr) {
    throw EncodeError("no IDL struct named '" + std::string(type_name) + "'");
  }
  Writer writer(schema, options);
  writer.writeStruct(*def, &value, "");
  return writer.take();
}

}  // namespace quad::introspection
