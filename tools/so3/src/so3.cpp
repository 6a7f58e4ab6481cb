// SPDX-License-Identifier: BSD-3-Clause
#include "quad/so3/so3.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <ostream>

#include <Eigen/Dense>

#include "quad/geometry/distance.hpp"
#include "quad/geometry/haar.hpp"

namespace quad::so3 {

namespace g = quad::geometry;

namespace {

const std::map<std::string, int> kArity = {
    {"--matrix", 9}, {"--quat", 4}, {"--axis-angle", 4}, {"--ypr", 3}};

double number(const std::string& option, const std::string& text)
{
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc{} || ptr != text.data() + text.size() || !std::isfinite(value)) {
    throw UsageError(option + ": '" + text + "' is not a finite number");
  }
  return value;
}

/// Ten significant digits; rounding noise below 1e-14 (and −0) printed as 0.
std::string fmt(double v)
{
  if (std::abs(v) < 1e-14) {
    v = 0.0;
  }
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.10g", v);
  return buffer;
}

std::string angleText(double radians)
{
  return fmt(radians) + " rad (" + fmt(radians * 180.0 / g::kPi) + " deg)";
}

std::string vectorText(const g::Vector3& v)
{
  return "(" + fmt(v.x()) + ", " + fmt(v.y()) + ", " + fmt(v.z()) + ")";
}

std::string quatText(const g::Quaternion& q)
{
  return "(" + fmt(q.w) + ", " + fmt(q.x) + ", " + fmt(q.y) + ", " + fmt(q.z) + ")";
}

RotationArgument build(const std::string& option, const std::vector<double>& v,
                       const So3Options& options, std::string text)
{
  const double unit = options.degrees ? g::kPi / 180.0 : 1.0;
  RotationArgument r;
  r.text = std::move(text);
  if (option == "--matrix") {
    g::Matrix3 A;
    A << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
    if (!g::isRotation(A, options.tolerance)) {
      const double orthogonality = (A.transpose() * A - g::Matrix3::Identity()).cwiseAbs().maxCoeff();
      throw UsageError("--matrix: not a rotation: max |AᵀA − I| = " + fmt(orthogonality) +
                       ", det A = " + fmt(A.determinant()) + " (tolerance " +
                       fmt(options.tolerance) + "; see --tolerance)");
    }
    r.q = g::fromMatrix(A);
  } else if (option == "--quat") {
    const g::Quaternion q{v[0], v[1], v[2], v[3]};
    const double n = q.norm();
    if (!(n > 1e-12)) {
      throw UsageError("--quat: the zero quaternion is no rotation");
    }
    if (std::abs(n - 1.0) > 1e-9) {
      r.note = "normalized from norm " + fmt(n);
    }
    r.q = q.normalized();
  } else if (option == "--axis-angle") {
    const g::Vector3 axis(v[0], v[1], v[2]);
    if (!(axis.norm() > 1e-12)) {
      throw UsageError("--axis-angle: the axis (0, 0, 0) has no direction");
    }
    r.q = g::fromAxisAngle(axis, v[3] * unit);
  } else {
    r.q = g::fromMatrix(g::matrixFromYpr({v[0] * unit, v[1] * unit, v[2] * unit}));
  }
  r.R = g::toMatrix(r.q);
  return r;
}

void printMatrix(const g::Matrix3& R, std::ostream& out)
{
  for (int row = 0; row < 3; ++row) {
    out << "  [" << fmt(R(row, 0)) << ", " << fmt(R(row, 1)) << ", " << fmt(R(row, 2)) << "]\n";
  }
}

}  // namespace

std::vector<RotationArgument> parseRotations(const std::vector<std::string>& args,
                                             const So3Options& options)
{
  std::vector<RotationArgument> out;
  for (std::size_t i = 0; i < args.size();) {
    const std::string& option = args[i];
    const auto arity = kArity.find(option);
    if (arity == kArity.end()) {
      throw UsageError("unexpected '" + option + "': give rotations as --matrix (9 numbers), "
                       "--quat (4: w x y z), --axis-angle (4: x y z angle) or --ypr (3)");
    }
    std::vector<double> values;
    std::string text = option;
    std::size_t j = i + 1;
    while (j < args.size() && !kArity.contains(args[j])) {
      values.push_back(number(option, args[j]));
      text += " " + args[j];
      ++j;
    }
    if (values.size() != static_cast<std::size_t>(arity->second)) {
      throw UsageError(option + ": expected " + std::to_string(arity->second) + " numbers, got " +
                       std::to_string(values.size()));
    }
    out.push_back(build(option, values, options, text));
    i = j;
  }
  return out;
}

void so3Convert(const std::vector<std::string>& args, const So3Options& options, std::ostream& out)
{
  const auto rotations = parseRotations(args, options);
  if (rotations.size() != 1) {
    throw UsageError("convert takes one rotation, got " + std::to_string(rotations.size()));
  }
  const RotationArgument& r = rotations.front();
  if (!r.note.empty()) {
    out << "note: " << r.note << "\n";
  }
  out << "matrix:\n";
  printMatrix(r.R, out);
  out << "quaternion (w, x, y, z): " << quatText(r.q.canonical()) << "  (and its negative)\n";
  const g::AxisAngle aa = g::axisAngleFromMatrix(r.R);
  out << "axis-angle: axis " << vectorText(aa.axis) << ", angle " << angleText(aa.angle);
  if (aa.angle == 0.0) {
    out << "  (any axis)";
  } else if (aa.angle == g::kPi) {
    out << "  (axis unique up to sign)";
  }
  out << "\n";
  out << "rotation vector (log): " << vectorText(g::logSO3(r.R)) << "\n";
  const g::YawPitchRoll ypr = g::yprFromMatrix(r.R);
  out << "yaw-pitch-roll (Z-Y-X): yaw " << angleText(ypr.yaw) << ", pitch " << angleText(ypr.pitch)
      << ", roll " << angleText(ypr.roll);
  if (std::abs(std::abs(ypr.pitch) - g::kPi / 2.0) < 1e-9) {
    out << "  (gimbal lock: only yaw " << (ypr.pitch > 0 ? "-" : "+") << " roll is determined)";
  }
  out << "\n";
}

void so3Distance(const std::vector<std::string>& args, const So3Options& options, std::ostream& out)
{
  const auto rotations = parseRotations(args, options);
  if (rotations.size() != 2) {
    throw UsageError("distance takes two rotations, got " + std::to_string(rotations.size()));
  }
  const RotationArgument& a = rotations[0];
  const RotationArgument& b = rotations[1];
  const g::Quaternion h1 = a.q.canonical();
  const g::Quaternion h2 = b.q.canonical();
  const double theta = g::geodesicAngle(a.R, b.R);
  out << "h1 = " << quatText(h1) << "   from " << a.text << "\n";
  out << "h2 = " << quatText(h2) << "   from " << b.text << "\n";
  out << "rotation angle between them (geodesic): " << angleText(theta) << "\n";
  out << "rho_s(h1, h2)   (eq. 5):  " << angleText(g::rhoS(h1, h2)) << "\n";
  out << "rho_s(h1, -h2)  (eq. 5):  " << angleText(g::rhoS(h1, -h2)) << "\n";
  out << "rho(h1, h2)     (eq. 6):  " << angleText(g::rho(h1, h2)) << "  = angle / 2\n";
  out << "yaw-pitch-roll  (eq. 15): "
      << fmt(g::yprDistance(g::yprFromMatrix(a.R), g::yprFromMatrix(b.R)))
      << " rad  (differences wrapped; not a distance between rotations)\n";
  out << "Frobenius in R9 (eq. 16): " << fmt(g::frobeniusDistance(a.R, b.R))
      << "  = 2 sqrt(2) sin(angle / 2)\n";
}

void so3Sample(int count, std::uint64_t seed, const std::string& as, const So3Options& options,
               std::ostream& out)
{
  if (count < 1) {
    throw UsageError("-n: " + std::to_string(count) + ": expected at least 1");
  }
  static const std::vector<std::string> kForms = {"quat", "matrix", "axis-angle", "ypr"};
  if (std::find(kForms.begin(), kForms.end(), as) == kForms.end()) {
    throw UsageError("--as: '" + as + "': expected quat, matrix, axis-angle or ypr");
  }
  const double unit = options.degrees ? 180.0 / g::kPi : 1.0;
  for (const auto& q : g::uniformRotations(static_cast<std::size_t>(count), seed)) {
    if (as == "quat") {
      out << fmt(q.w) << " " << fmt(q.x) << " " << fmt(q.y) << " " << fmt(q.z) << "\n";
    } else if (as == "matrix") {
      const g::Matrix3 R = g::toMatrix(q);
      for (int k = 0; k < 9; ++k) {
        out << (k == 0 ? "" : " ") << fmt(R(k / 3, k % 3));
      }
      out << "\n";
    } else if (as == "axis-angle") {
      const g::AxisAngle aa = g::axisAngleFromMatrix(g::toMatrix(q));
      out << fmt(aa.axis.x()) << " " << fmt(aa.axis.y()) << " " << fmt(aa.axis.z()) << " "
          << fmt(aa.angle * unit) << "\n";
    } else {
      const g::YawPitchRoll ypr = g::yprFromMatrix(g::toMatrix(q));
      out << fmt(ypr.yaw * unit) << " " << fmt(ypr.pitch * unit) << " " << fmt(ypr.roll * unit) << "\n";
    }
  }
}

}  // namespace quad::so3
