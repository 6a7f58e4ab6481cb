// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// How far the estimator's state was from the truth over a run, and whether its own 1σ said
/// so: each estimate is paired with the true state of the same stamp (both follow the plant's
/// steps) and scored while the filter is aligned, up to the run's end (endAt).

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "quad/geometry/quaternion.hpp"

namespace quad::launch {

/// The position's figures over the pairs whose true speed lies in [from_mps, to_mps).
struct EstimateBand {
  double from_mps = 0.0;
  double to_mps = 0.0;                ///< infinity for the last band
  std::uint64_t samples = 0;
  double position_rms_m = 0.0;
  double position_nees_mean = 0.0;
};

struct EstimateErrors {
  std::uint64_t samples = 0;          ///< estimates paired with a true state
  double position_rms_m = 0.0;        ///< of the position error's norm
  double position_max_m = 0.0;
  double attitude_rms_deg = 0.0;      ///< of the rotation between estimate and truth
  double attitude_max_deg = 0.0;
  double yaw_rms_deg = 0.0;           ///< of the heading error alone
  /// Mean position NEES, Σ (e_i / σ_i)² over the axes with the estimate's per-axis 1σ: 3 for
  /// a consistent filter, more for an overconfident one.
  double position_nees_mean = 0.0;
  /// Share of samples whose position error is within 3σ on every axis.
  double within_3sigma = 0.0;
  /// The same by the vehicle's true speed (EstimateScore::kSpeedBands), the bands that hold
  /// pairs only: whether the filter stays consistent when it flies fast.
  std::vector<EstimateBand> by_speed;
};

/// One point of the error against time: the first pair scored in each `kSeriesPeriodNs` of
/// sim time.
struct EstimateErrorPoint {
  double t_s = 0.0;             ///< [s] sim time
  double position_m = 0.0;      ///< the position error's norm
  double position_3sigma_m = 0.0;  ///< the norm of the estimate's per-axis 3σ: its own bound on that
  double attitude_deg = 0.0;
  double yaw_deg = 0.0;         ///< signed, estimate less truth
};

class EstimateScore {
public:
  static constexpr std::int64_t kSeriesPeriodNs = 100'000'000;  ///< 10 points a second
  /// [m/s] The lower edges of the speed bands: below 2, 2 to 5, 5 and more (a flight at the
  /// shipped speed, a fast one, the benchmark's cruise).
  static constexpr std::array<double, 3> kSpeedBands{0.0, 2.0, 5.0};
  /// The true body position [m], attitude and velocity [m/s] at `t_ns`.
  void onTruth(std::int64_t t_ns, const geometry::Vector3& p_W, const geometry::Quaternion& q_WB,
               const geometry::Vector3& v_W);
  /// An estimate at `t_ns` with its per-axis position 1σ [m]; not aligned: not scored.
  void onEstimate(std::int64_t t_ns, const geometry::Vector3& p_W, const geometry::Quaternion& q_WB,
                  const geometry::Vector3& p_std, bool aligned);
  /// Scores nothing stamped after `t_ns` from now on, and drops what was (kHoldNs of sim
  /// time back): the pairs a run scores end where its mission ended, however late that end
  /// is heard beside the samples that came meanwhile.
  void endAt(std::int64_t t_ns);
  /// Nothing before the first pair.
  std::optional<EstimateErrors> errors() const;
  /// The error against time (10 points a second; a run of an hour holds 36,000).
  std::vector<EstimateErrorPoint> series() const;
  /// [ns] How far behind the newest pair a pair stays revocable by endAt.
  static constexpr std::int64_t kHoldNs = 10'000'000'000;

private:
  struct Pose {
    geometry::Vector3 p;
    geometry::Quaternion q;
    geometry::Vector3 std;    ///< an estimate's per-axis 1σ
    double speed = 0.0;       ///< the truth's [m/s]
  };
  /// A band's sums.
  struct BandSums {
    std::uint64_t n = 0;
    double sum_p2 = 0.0;
    double sum_nees = 0.0;
  };
  /// One pair's errors.
  struct Term {
    double position_m;
    double position_3sigma_m;
    double attitude_deg;
    double yaw_deg;
    double nees;
    bool within_3sigma;
    double speed;
  };
  void score(std::int64_t t_ns, const Pose& truth, const Pose& estimate);
  /// Adds the held pairs stamped before `t_ns` to the totals, in stamp order.
  void commitBefore(std::int64_t t_ns);
  /// A copy with every held pair added up.
  EstimateScore committed() const;
  /// Samples waiting for their other half, by stamp; bounded.
  std::map<std::int64_t, Pose> truths_;
  std::map<std::int64_t, Pose> estimates_;
  std::map<std::int64_t, Term> held_;  // scored within kHoldNs of the newest, not yet added up
  std::int64_t end_ns_ = std::numeric_limits<std::int64_t>::max();
  std::uint64_t n_ = 0;
  double sum_p2_ = 0.0;
  double max_p_ = 0.0;
  double sum_a2_ = 0.0;
  double max_a_ = 0.0;
  double sum_yaw2_ = 0.0;
  double sum_nees_ = 0.0;
  std::uint64_t within_ = 0;
  std::array<BandSums, kSpeedBands.size()> bands_{};
  std::vector<EstimateErrorPoint> series_;
  std::int64_t next_point_ns_ = 0;
};

/// The series as CSV with a header line: t_s, position_m, position_3sigma_m, attitude_deg, yaw_deg.
std::string toCsv(const std::vector<EstimateErrorPoint>& series);

}  // namespace quad::launch
