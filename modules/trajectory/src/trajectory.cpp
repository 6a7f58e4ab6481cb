// SPDX-License-Identifier: BSD-3-Clause
#include "quad/trajectory/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace quad::trajectory {

namespace {

/// The d-th derivative of Σ cₖ τᵏ with respect to τ, at τ (Horner's rule on the derived
/// coefficients k!/(k−d)! cₖ).
Vector3 derivative(const Coefficients& c, int d, double tau)
{
  Vector3 sum = Vector3::Zero();
  for (int k = kCoefficients - 1; k >= d; --k) {
    double falling = 1.0;  // k (k−1) … (k−d+1)
    for (int m = 0; m < d; ++m) {
      falling *= k - m;
    }
    sum = sum * tau + falling * c.col(k);
  }
  return sum;
}

}  // namespace

State Piece::at(double t) const
{
  const double tau = std::clamp(t / duration, 0.0, 1.0);
  const double inv = 1.0 / duration;
  return State{derivative(c, 0, tau), derivative(c, 1, tau) * inv, derivative(c, 2, tau) * inv * inv,
               derivative(c, 3, tau) * inv * inv * inv};
}

Vector3 Piece::snap(double t) const
{
  const double tau = std::clamp(t / duration, 0.0, 1.0);
  return derivative(c, 4, tau) / std::pow(duration, 4);
}

Trajectory::Trajectory(double start_time, std::vector<Piece> pieces) : start_(start_time), pieces_(std::move(pieces))
{
  if (pieces_.empty()) {
    throw std::invalid_argument("Trajectory: no piece");
  }
  if (!std::isfinite(start_time)) {
    throw std::invalid_argument("Trajectory: start time " + std::to_string(start_time) + " is not finite");
  }
  double end = start_;
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    const Piece& p = pieces_[i];
    if (!(p.duration > 0.0) || !std::isfinite(p.duration) || !p.c.allFinite()) {
      throw std::invalid_argument("Trajectory: piece " + std::to_string(i) + " has duration " +
                                  std::to_string(p.duration) + " s or a coefficient that is not finite");
    }
    end += p.duration;
    ends_.push_back(end);
  }
}

std::pair<std::size_t, double> Trajectory::locate(double t) const
{
  const auto it = std::upper_bound(ends_.begin(), ends_.end(), t);
  const std::size_t i = std::min(static_cast<std::size_t>(it - ends_.begin()), pieces_.size() - 1);
  const double piece_start = i == 0 ? start_ : ends_[i - 1];
  return {i, t - piece_start};
}

State Trajectory::at(double t) const
{
  if (pieces_.empty()) {
    return {};
  }
  if (t >= endTime()) {
    return State{pieces_.back().at(pieces_.back().duration).p, Vector3::Zero(), Vector3::Zero(), Vector3::Zero()};
  }
  if (t <= start_) {
    return pieces_.front().at(0.0);
  }
  const auto [i, local] = locate(t);
  return pieces_[i].at(local);
}

double Trajectory::length(double from, double to) const
{
  // Simpson's rule on the speed, a few steps a piece: a curve of degree 7 is smooth enough.
  from = std::max(from, start_);
  to = std::min(to, endTime());
  if (!(to > from)) {
    return 0.0;
  }
  const int steps = 2 * std::max<int>(8, static_cast<int>(std::ceil(8.0 * static_cast<double>(pieces_.size()) *
                                                                     (to - from) / std::max(duration(), 1e-9))));
  const double h = (to - from) / steps;
  const auto speed = [this](double t) {
    const auto [i, local] = locate(t);  // at the very end, the last piece's own end
    return pieces_[i].at(local).v.norm();
  };
  double sum = speed(from) + speed(to);
  for (int k = 1; k < steps; ++k) {
    sum += (k % 2 == 1 ? 4.0 : 2.0) * speed(from + k * h);
  }
  return sum * h / 3.0;
}

Trajectory restingAt(const Vector3& p, double start_time, double duration)
{
  Piece piece;
  piece.duration = duration;
  piece.c.col(0) = p;
  return Trajectory(start_time, {piece});
}

}  // namespace quad::trajectory
