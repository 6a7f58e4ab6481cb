// SPDX-License-Identifier: BSD-3-Clause
#include "quad/world/point_cloud_file.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

namespace quad::world {

namespace {

using geometry::Vector3;

/// A scalar as stored in a file: its size, kind and byte order.
struct Scalar {
  enum class Kind { kSigned, kUnsigned, kFloat };
  Kind kind = Kind::kFloat;
  int size = 4;  // [bytes]
};

/// The value of `size` bytes of `kind`, in the file's byte order.
double decode(const char* bytes, Scalar s, bool big_endian)
{
  unsigned char b[8];
  std::memcpy(b, bytes, static_cast<std::size_t>(s.size));
  if (big_endian != (std::endian::native == std::endian::big)) {
    std::reverse(b, b + s.size);
  }
  const auto as = [&b]<typename T>(T) {
    T v;
    std::memcpy(&v, b, sizeof v);
    return static_cast<double>(v);
  };
  switch (s.kind) {
    case Scalar::Kind::kFloat:
      return s.size == 8 ? as(double{}) : as(float{});
    case Scalar::Kind::kSigned:
      return s.size == 1 ? as(std::int8_t{}) : s.size == 2 ? as(std::int16_t{}) : s.size == 4 ? as(std::int32_t{}) : as(std::int64_t{});
    case Scalar::Kind::kUnsigned:
      return s.size == 1 ? as(std::uint8_t{}) : s.size == 2 ? as(std::uint16_t{}) : s.size == 4 ? as(std::uint32_t{}) : as(std::uint64_t{});
  }
  return 0.0;
}

class Reader {
public:
  explicit Reader(const std::filesystem::path& file) : file_(file), in_(file, std::ios::binary)
  {
    if (!in_) {
      fail("cannot open it: " + std::string(std::strerror(errno)));
    }
  }

  [[noreturn]] void fail(const std::string& why) const
  {
    throw PointCloudError(file_.string() + (line_ > 0 ? ": line " + std::to_string(line_) : std::string()) + ": " + why);
  }

  /// The next header line, without its line end; fails at the end of the file.
  std::string headerLine()
  {
    std::string line;
    if (!std::getline(in_, line)) {
      fail("the header ends before " + std::string(end_of_header_));
    }
    ++line_;
    if (!line.empty() && line.back() == '\r') {
      line.pop_back();
    }
    return line;
  }

  void expectEndOfHeader(const char* what) { end_of_header_ = what; }

  /// The next whitespace-separated number of an ASCII body.
  double token()
  {
    std::string t;
    if (!(in_ >> t)) {
      endOfBody("a number");
    }
    try {
      std::size_t used = 0;
      const double v = std::stod(t, &used);
      if (used != t.size()) {
        throw std::invalid_argument(t);
      }
      return v;
    } catch (const std::logic_error&) {
      // "nan" and "inf" parse; anything else is not a number
      bodyFail("'" + t + "' is not a number");
    }
  }

  /// The next `size` bytes of a binary body.
  const char* bytes(int size)
  {
    buffer_.resize(static_cast<std::size_t>(size));
    if (!in_.read(buffer_.data(), size)) {
      endOfBody(std::to_string(size) + " more bytes");
    }
    return buffer_.data();
  }

  [[noreturn]] void endOfBody(const std::string& wanted)
  {
    line_ = 0;
    fail("the data ends early (point " + std::to_string(point_) + " of " + std::to_string(points_) + " wanted " +
         wanted + "): the file is truncated or its header's counts are wrong");
  }
  [[noreturn]] void bodyFail(const std::string& why)
  {
    line_ = 0;
    fail("point " + std::to_string(point_) + ": " + why);
  }

  void countPoints(std::int64_t n) { points_ = n; }
  void atPoint(std::int64_t i) { point_ = i; }

private:
  std::filesystem::path file_;
  std::ifstream in_;
  std::string buffer_;
  int line_ = 0;
  const char* end_of_header_ = "its end";
  std::int64_t points_ = 0;
  std::int64_t point_ = 0;
};

std::vector<std::string> words(const std::string& line)
{
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) {
    out.push_back(w);
  }
  return out;
}

std::int64_t count(Reader& r, const std::string& text, const std::string& what)
{
  try {
    std::size_t used = 0;
    const long long n = std::stoll(text, &used);
    if (used == text.size() && n >= 0) {
      return n;
    }
  } catch (const std::logic_error&) {
  }
  r.fail(what + " '" + text + "' is not a count");
}

/// Keeps a finite point; a point without a return (NaN, as organised clouds store them) is
/// not an obstacle and is dropped.
void keep(std::vector<Vector3>& out, const Vector3& p)
{
  if (p.allFinite()) {
    out.push_back(p);
  }
}

// ---- PLY ----

struct PlyProperty {
  std::string name;
  Scalar type;
  std::optional<Scalar> list_count;  // a list property: its count's type (type is the items')
};

struct PlyElement {
  std::string name;
  std::int64_t count = 0;
  std::vector<PlyProperty> properties;
};

std::optional<Scalar> plyType(const std::string& t)
{
  using K = Scalar::Kind;
  if (t == "char" || t == "int8") return Scalar{K::kSigned, 1};
  if (t == "uchar" || t == "uint8") return Scalar{K::kUnsigned, 1};
  if (t == "short" || t == "int16") return Scalar{K::kSigned, 2};
  if (t == "ushort" || t == "uint16") return Scalar{K::kUnsigned, 2};
  if (t == "int" || t == "int32") return Scalar{K::kSigned, 4};
  if (t == "uint" || t == "uint32") return Scalar{K::kUnsigned, 4};
  if (t == "float" || t == "float32") return Scalar{K::kFloat, 4};
  if (t == "double" || t == "float64") return Scalar{K::kFloat, 8};
  return std::nullopt;
}

std::vector<Vector3> readPly(Reader& r)
{
  r.expectEndOfHeader("end_header");
  if (r.headerLine() != "ply") {
    r.fail("not a PLY file: it does not start with 'ply'");
  }
  enum class Format { kAscii, kLittle, kBig } format = Format::kAscii;
  bool has_format = false;
  std::vector<PlyElement> elements;
  for (std::string line = r.headerLine(); line != "end_header"; line = r.headerLine()) {
    const auto w = words(line);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") {
      continue;
    }
    if (w[0] == "format") {
      if (w.size() != 3 || w[2] != "1.0") {
        r.fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0', not '" + line + "'");
      }
      if (w[1] == "ascii") format = Format::kAscii;
      else if (w[1] == "binary_little_endian") format = Format::kLittle;
      else if (w[1] == "binary_big_endian") format = Format::kBig;
      else r.fail("unknown format '" + w[1] + "'");
      has_format = true;
    } else if (w[0] == "element") {
      if (w.size() != 3) {
        r.fail("expected 'element NAME COUNT', not '" + line + "'");
      }
      elements.push_back({w[1], count(r, w[2], "element " + w[1] + "'s count"), {}});
    } else if (w[0] == "property") {
      if (elements.empty()) {
        r.fail("a property before any element");
      }
      const bool list = w.size() == 5 && w[1] == "list";
      if (!list && w.size() != 3) {
        r.fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME', not '" + line + "'");
      }
      const auto type = plyType(w[list ? 3 : 1]);
      const auto count_type = list ? plyType(w[2]) : std::nullopt;
      if (!type || (list && (!count_type || count_type->kind == Scalar::Kind::kFloat))) {
        r.fail("unknown property type in '" + line + "'");
      }
      elements.back().properties.push_back({w.back(), *type, count_type});
    } else {
      r.fail("unknown header line '" + line + "'");
    }
  }
  if (!has_format) {
    r.fail("the header has no format line");
  }
  const auto vertex = std::find_if(elements.begin(), elements.end(), [](const PlyElement& e) { return e.name == "vertex"; });
  if (vertex == elements.end()) {
    r.fail("no 'element vertex': the file holds no points");
  }
  std::array<int, 3> xyz{-1, -1, -1};
  for (std::size_t i = 0; i < vertex->properties.size(); ++i) {
    const PlyProperty& p = vertex->properties[i];
    for (int a = 0; a < 3; ++a) {
      if (p.name == std::string(1, static_cast<char>('x' + a)) && !p.list_count) {
        xyz[static_cast<std::size_t>(a)] = static_cast<int>(i);
      }
    }
  }
  for (int a = 0; a < 3; ++a) {
    if (xyz[static_cast<std::size_t>(a)] < 0) {
      r.fail(std::string("element vertex has no scalar property ") + static_cast<char>('x' + a));
    }
  }
  const bool big = format == Format::kBig;
  const auto value = [&](Scalar s) { return format == Format::kAscii ? r.token() : decode(r.bytes(s.size), s, big); };
  std::vector<Vector3> points;
  for (auto e = elements.begin(); e != vertex + 1; ++e) {
    const bool is_vertex = e == vertex;
    if (is_vertex) {
      points.reserve(static_cast<std::size_t>(std::min<std::int64_t>(e->count, 1 << 24)));
      r.countPoints(e->count);
    }
    for (std::int64_t k = 0; k < e->count; ++k) {
      r.atPoint(k);
      Vector3 p = Vector3::Zero();
      for (std::size_t i = 0; i < e->properties.size(); ++i) {
        const PlyProperty& prop = e->properties[i];
        if (prop.list_count) {
          const double n = value(*prop.list_count);
          for (double j = 0; j < n; ++j) {
            (void)value(prop.type);
          }
          continue;
        }
        const double v = value(prop.type);
        for (int a = 0; a < 3; ++a) {
          if (is_vertex && static_cast<int>(i) == xyz[static_cast<std::size_t>(a)]) {
            p[a] = v;
          }
        }
      }
      if (is_vertex) {
        keep(points, p);
      }
    }
  }
  return points;
}

// ---- PCD ----

std::vector<Vector3> readPcd(Reader& r)
{
  r.expectEndOfHeader("its DATA line");
  std::vector<std::string> fields;
  std::vector<int> sizes;
  std::vector<char> types;
  std::vector<int> counts;
  std::int64_t points = -1;
  std::string data;
  while (data.empty()) {
    const std::string line = r.headerLine();
    const auto w = words(line);
    if (w.empty() || w[0].front() == '#') {
      continue;
    }
    const std::vector<std::string> rest(w.begin() + 1, w.end());
    if (w[0] == "FIELDS") {
      fields = rest;
    } else if (w[0] == "SIZE" || w[0] == "COUNT") {
      auto& out = w[0] == "SIZE" ? sizes : counts;
      for (const auto& s : rest) {
        const std::int64_t n = count(r, s, w[0]);
        if (n < 1 || n > (w[0] == "SIZE" ? 8 : 1 << 20) || (w[0] == "SIZE" && (n & (n - 1)) != 0)) {
          r.fail(w[0] + " '" + s + "' is out of range");
        }
        out.push_back(static_cast<int>(n));
      }
    } else if (w[0] == "TYPE") {
      for (const auto& s : rest) {
        if (s != "I" && s != "U" && s != "F") {
          r.fail("TYPE '" + s + "' is not I, U or F");
        }
        types.push_back(s[0]);
      }
    } else if (w[0] == "POINTS") {
      if (rest.size() != 1) {
        r.fail("expected 'POINTS N'");
      }
      points = count(r, rest[0], "POINTS");
    } else if (w[0] == "DATA") {
      if (rest.size() != 1) {
        r.fail("expected 'DATA ascii|binary'");
      }
      data = rest[0];
    } else if (w[0] != "VERSION" && w[0] != "WIDTH" && w[0] != "HEIGHT" && w[0] != "VIEWPOINT") {
      r.fail("unknown header line '" + line + "'");
    }
  }
  if (data != "ascii" && data != "binary") {
    r.fail("DATA " + data + " is not read: save the cloud as ascii or binary");
  }
  if (counts.empty()) {
    counts.assign(fields.size(), 1);
  }
  if (fields.empty() || sizes.size() != fields.size() || types.size() != fields.size() || counts.size() != fields.size()) {
    r.fail("FIELDS, SIZE, TYPE and COUNT must name the same number of fields");
  }
  if (points < 0) {
    r.fail("the header has no POINTS line");
  }
  std::array<int, 3> xyz{-1, -1, -1};
  for (std::size_t i = 0; i < fields.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      if (fields[i] == std::string(1, static_cast<char>('x' + a))) {
        xyz[static_cast<std::size_t>(a)] = static_cast<int>(i);
      }
    }
  }
  for (int a = 0; a < 3; ++a) {
    if (xyz[static_cast<std::size_t>(a)] < 0) {
      r.fail(std::string("FIELDS has no ") + static_cast<char>('x' + a));
    }
  }
  r.countPoints(points);
  std::vector<Vector3> out;
  out.reserve(static_cast<std::size_t>(std::min<std::int64_t>(points, 1 << 24)));
  for (std::int64_t k = 0; k < points; ++k) {
    r.atPoint(k);
    Vector3 p = Vector3::Zero();
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const Scalar s{types[i] == 'F' ? Scalar::Kind::kFloat : types[i] == 'I' ? Scalar::Kind::kSigned : Scalar::Kind::kUnsigned,
                     sizes[i]};
      if (s.kind == Scalar::Kind::kFloat && s.size != 4 && s.size != 8) {
        r.fail("a float field of size " + std::to_string(s.size));
      }
      for (int c = 0; c < counts[i]; ++c) {
        // PCL writes binary data in the writer's byte order: little-endian on every machine it runs on
        const double v = data == "ascii" ? r.token() : decode(r.bytes(s.size), s, false);
        for (int a = 0; a < 3; ++a) {
          if (c == 0 && static_cast<int>(i) == xyz[static_cast<std::size_t>(a)]) {
            p[a] = v;
          }
        }
      }
    }
    keep(out, p);
  }
  return out;
}

}  // namespace

std::vector<Vector3> readPointCloud(const std::filesystem::path& file)
{
  const std::string ext = file.extension().string();
  if (ext != ".ply" && ext != ".pcd") {
    throw PointCloudError(file.string() + ": not a point cloud: expected a .ply or .pcd file");
  }
  Reader r(file);
  return ext == ".ply" ? readPly(r) : readPcd(r);
}

}  // namespace quad::world
