// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad so3 ...`: the guide's rotation chapter on the command line, for students.
///
/// Rotations are given as groups of numbers: `--matrix` and 9 numbers (row by row),
/// `--quat` and 4 (w x y z, scalar first), `--axis-angle` and 4 (axis x y z, angle),
/// `--ypr` and 3 (yaw pitch roll, Z-Y-X). Angles are radians, or degrees after `--degrees`.

#include <cstdint>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

#include "quad/geometry/quaternion.hpp"

namespace quad::so3 {

/// Bad input on the command line: the message names the option and the value. Exit code 2.
class UsageError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct RotationArgument {
  std::string text;            ///< as typed, for messages ("--quat 1 1 0 0")
  geometry::Quaternion q;      ///< normalized
  geometry::Matrix3 R;
  std::string note;            ///< e.g. "normalized from norm 1.41421"
};

struct So3Options {
  bool degrees = false;        ///< angles in and out in degrees
  double tolerance = 1e-6;     ///< for the SO(3) membership check of --matrix input
};

/// Parses `args` into rotations; throws UsageError on an unknown option, a wrong count, a
/// non-number, a matrix that is not a rotation, a zero quaternion or axis.
std::vector<RotationArgument> parseRotations(const std::vector<std::string>& args,
                                             const So3Options& options);

/// Prints one rotation in every representation. Throws UsageError unless exactly one is given.
void so3Convert(const std::vector<std::string>& args, const So3Options& options, std::ostream& out);

/// Prints every distance between two rotations. Throws UsageError unless exactly two are given.
void so3Distance(const std::vector<std::string>& args, const So3Options& options, std::ostream& out);

/// Prints `count` Haar-uniform rotations from `seed`, as quaternions, matrices, axis-angle or
/// yaw-pitch-roll (`as`).
void so3Sample(int count, std::uint64_t seed, const std::string& as, const So3Options& options,
               std::ostream& out);

}  // namespace quad::so3
