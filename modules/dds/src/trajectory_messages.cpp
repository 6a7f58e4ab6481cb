// SPDX-License-Identifier: BSD-3-Clause
#include "quad/dds/trajectory_messages.hpp"

#include <cmath>
#include <stdexcept>

#include "quad/common/time.hpp"

namespace quad::dds {

namespace {
/// The IDL's bound on pieces (Trajectory.idl).
constexpr std::size_t kMaxPieces = 512;
}  // namespace

msg::Trajectory toMessage(const trajectory::Trajectory& t, std::uint32_t count, std::uint32_t path_version)
{
  msg::Trajectory m;
  m.count(count);
  m.path_version(path_version);
  m.start_ns(common::toNanoseconds(t.startTime()));
  m.depth_stamp_ns(-1);  // the caller's to set when it follows a path
  for (std::size_t i = 0; i < t.pieces().size() && i < kMaxPieces; ++i) {
    const trajectory::Piece& p = t.pieces()[i];
    msg::TrajectoryPiece out;
    out.duration(p.duration);
    for (int axis = 0; axis < 3; ++axis) {
      for (int k = 0; k < trajectory::kCoefficients; ++k) {
        out.coefficients()[static_cast<std::size_t>(axis * trajectory::kCoefficients + k)] = p.c(axis, k);
      }
    }
    m.pieces().push_back(out);
  }
  return m;
}

std::optional<trajectory::Trajectory> fromMessage(const msg::Trajectory& m, std::string* why)
{
  std::vector<trajectory::Piece> pieces;
  for (const msg::TrajectoryPiece& in : m.pieces()) {
    trajectory::Piece p;
    p.duration = in.duration();
    for (int axis = 0; axis < 3; ++axis) {
      for (int k = 0; k < trajectory::kCoefficients; ++k) {
        p.c(axis, k) = in.coefficients()[static_cast<std::size_t>(axis * trajectory::kCoefficients + k)];
      }
    }
    pieces.push_back(p);
  }
  try {
    return trajectory::Trajectory(common::toSeconds(m.start_ns()), std::move(pieces));
  } catch (const std::invalid_argument& e) {
    if (why) {
      *why = e.what();
    }
    return std::nullopt;
  }
}

}  // namespace quad::dds
