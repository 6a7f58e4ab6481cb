// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The estimate's error against time as a picture: an SVG file any browser opens, written next
/// to a run's summary. Two panels on one time axis: the position error with the estimate's
/// own 3σ bound on it, and the attitude and heading errors.

#include <string>
#include <vector>

#include "quad/launch/estimate_score.hpp"

namespace quad::launch {

/// The series as a standalone SVG document titled `title`; a series of fewer than two points
/// gives an SVG saying so.
std::string estimateErrorSvg(const std::vector<EstimateErrorPoint>& series, const std::string& title);

}  // namespace quad::launch
