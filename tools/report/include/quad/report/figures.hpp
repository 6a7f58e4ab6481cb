// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The report's figures of a flight, each an SVG document with its file name and caption.

#include <optional>
#include <string>
#include <vector>

#include "quad/report/flight.hpp"
#include "quad/world/world.hpp"

namespace quad::report {

struct Figure {
  std::string file;     ///< "top_view.svg"
  std::string caption;  ///< a sentence under it
  std::string svg;
};

/// Every figure the flight has data for, in the report's order: the top and side views (with
/// `world`'s obstacles when given), altitude, speed and distance to goal, tracking error, the
/// modes' timeline, replanning, topic rates, and the estimate's error when an estimator ran.
std::vector<Figure> flightFigures(const FlightData& flight, const world::World* world);

/// A reaction a fault scenario timed (quad fault's fault_report.json).
struct Reaction {
  std::string label;  ///< "2: mode HOVER"
  double within_s = 0.0;
  std::optional<double> measured_s;  ///< nothing: it did not come in time
};
/// The reactions' measured times against their bounds.
Figure reactionsFigure(const std::string& scenario, const std::vector<Reaction>& reactions);

}  // namespace quad::report
