// SPDX-License-Identifier: BSD-3-Clause
#include "quad/trajectory/min_snap.hpp"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <array>
#include <cmath>

namespace quad::trajectory {

namespace {

constexpr int kN = kCoefficients;
/// Derivatives fixed at the start and at the end: position, velocity, acceleration, jerk.
constexpr int kEndDerivatives = 4;
/// Derivatives continuous at an interior point besides the position: 1 … 6.
constexpr int kContinuous = kN - 2;

/// k (k−1) … (k−d+1): the factor d derivatives in τ bring down on τᵏ.
double falling(int k, int d)
{
  double f = 1.0;
  for (int m = 0; m < d; ++m) {
    f *= k - m;
  }
  return f;
}

Vector3 derivativeOf(const State& s, int d)
{
  switch (d) {
    case 0:
      return s.p;
    case 1:
      return s.v;
    case 2:
      return s.a;
    default:
      return s.j;
  }
}

bool finite(const State& s) { return s.p.allFinite() && s.v.allFinite() && s.a.allFinite() && s.j.allFinite(); }

}  // namespace

std::optional<std::vector<Piece>> minimumSnap(const State& start, const std::vector<Vector3>& through,
                                              const State& end, const std::vector<double>& durations)
{
  const std::size_t pieces = durations.size();
  if (pieces == 0 || through.size() + 1 != pieces || !finite(start) || !finite(end)) {
    return std::nullopt;
  }
  for (const double T : durations) {
    if (!(T > 0.0) || !std::isfinite(T)) {
      return std::nullopt;
    }
  }
  for (const Vector3& w : through) {
    if (!w.allFinite()) {
      return std::nullopt;
    }
  }
  const Eigen::Index n = static_cast<Eigen::Index>(kN * pieces);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(n) * 6);
  Eigen::Matrix<double, Eigen::Dynamic, 3> rhs = Eigen::Matrix<double, Eigen::Dynamic, 3>::Zero(n, 3);
  Eigen::Index row = 0;
  const auto column = [](std::size_t piece, int k) {
    return static_cast<Eigen::Index>(kN * piece) + static_cast<Eigen::Index>(k);
  };

  // The start: dᵈp/dtᵈ = T⁻ᵈ d! c_d at τ = 0, written as d! c_d = Tᵈ sᵈ.
  const double T0 = durations.front();
  for (int d = 0; d < kEndDerivatives; ++d, ++row) {
    entries.emplace_back(row, column(0, d), falling(d, d));
    rhs.row(row) = (derivativeOf(start, d) * std::pow(T0, d)).transpose();
  }
  // The end, at τ = 1 of the last piece: Σₖ k!/(k−d)! cₖ = Tᵈ eᵈ.
  const std::size_t last = pieces - 1;
  const double Tn = durations.back();
  for (int d = 0; d < kEndDerivatives; ++d, ++row) {
    for (int k = d; k < kN; ++k) {
      entries.emplace_back(row, column(last, k), falling(k, d));
    }
    rhs.row(row) = (derivativeOf(end, d) * std::pow(Tn, d)).transpose();
  }
  // Each interior point: both pieces pass it, and derivatives 1 … 6 agree. The derivative d
  // of piece i−1 at its end is Tᵢ₋₁⁻ᵈ Σₖ k!/(k−d)! cₖ, of piece i at its start Tᵢ⁻ᵈ d! c_d; the
  // equation is scaled by (Tᵢ₋₁ Tᵢ)^(d/2) so that only the square root of the durations'
  // ratio enters each side (pieces of unequal length stay well conditioned).
  for (std::size_t i = 1; i < pieces; ++i, ++row) {
    for (int k = 0; k < kN; ++k) {
      entries.emplace_back(row, column(i - 1, k), 1.0);
    }
    rhs.row(row) = through[i - 1].transpose();
    ++row;
    entries.emplace_back(row, column(i, 0), 1.0);
    rhs.row(row) = through[i - 1].transpose();
    const double ratio = std::sqrt(durations[i] / durations[i - 1]);  // √(Tᵢ / Tᵢ₋₁)
    for (int d = 1; d <= kContinuous; ++d) {
      ++row;
      const double before = std::pow(ratio, d);
      for (int k = d; k < kN; ++k) {
        entries.emplace_back(row, column(i - 1, k), before * falling(k, d));
      }
      entries.emplace_back(row, column(i, d), -falling(d, d) / before);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(A);
  if (lu.info() != Eigen::Success) {
    return std::nullopt;
  }
  const Eigen::Matrix<double, Eigen::Dynamic, 3> x = lu.solve(rhs);
  if (lu.info() != Eigen::Success || !x.allFinite()) {
    return std::nullopt;
  }
  std::vector<Piece> out(pieces);
  for (std::size_t i = 0; i < pieces; ++i) {
    out[i].duration = durations[i];
    out[i].c = x.middleRows(static_cast<Eigen::Index>(kN * i), kN).transpose();
  }
  return out;
}

double snapCost(const std::vector<Piece>& pieces)
{
  // Four-point Gauss–Legendre on [0, 1]: exact for polynomials up to degree 7, and ‖p⁽⁴⁾‖² is
  // of degree 6.
  static constexpr std::array<double, 4> kNodes{0.0694318442029737, 0.3300094782075719, 0.6699905217924281,
                                                 0.9305681557970263};
  static constexpr std::array<double, 4> kWeights{0.1739274225687269, 0.3260725774312731, 0.3260725774312731,
                                                   0.1739274225687269};
  double cost = 0.0;
  for (const Piece& p : pieces) {
    for (std::size_t q = 0; q < kNodes.size(); ++q) {
      cost += kWeights[q] * p.duration * p.snap(kNodes[q] * p.duration).squaredNorm();
    }
  }
  return cost;
}

}  // namespace quad::trajectory
