// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Figures as standalone SVG documents any browser opens, with nothing to install: panels of
/// series on one shared axis, an equal-scale drawing in metres (a map's top or side view), a
/// timeline of intervals, and bars against a reference. Written directly: the figures are
/// lines, dots, rectangles and text, which SVG states in a line each.

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace quad::report {

/// An axis widened to whole, round ticks (1, 2 or 5 times a power of ten).
struct Axis {
  double lo = 0.0;
  double hi = 1.0;
  double step = 0.2;
};
/// About five ticks over [lo, hi]; a flat or empty span gets a span of 1, a non-finite one
/// [0, 1].
Axis axisOver(double lo, double hi);
/// The axis's tick values, lo first (none for a non-finite axis; never more than 61).
std::vector<double> ticks(const Axis& axis);

using Point = std::pair<double, double>;  ///< (x, y) in the data's units

struct Series {
  enum class Style { kLine, kSteps, kDots };
  std::vector<Point> points;  ///< in increasing x for lines and steps
  std::string colour = "#1f5fbf";
  std::string label;
  Style style = Style::kLine;
  std::string dash;  ///< stroke-dasharray, "" for solid
};

/// One panel: series on a value axis labelled `unit`. The value axis spans every point, and
/// `lo`/`hi` when given (to keep zero in view, say).
struct Panel {
  std::string unit;
  std::vector<Series> series;
  std::optional<double> lo;
  std::optional<double> hi;
  bool log_scale = false;  ///< a base-10 axis (values <= 0 are left out)
};

/// Panels stacked over one x axis labelled `x_label`. Panels with no point say so in place.
std::string stackedChartSvg(const std::string& title, const std::string& x_label, const std::vector<Panel>& panels);

/// A drawing in metres at one scale on both axes (squares stay square): a top or a side view.
class PlanView {
public:
  /// The view spans [x_lo, x_hi] × [y_lo, y_hi] and is `width` pixels wide.
  PlanView(std::string title, std::string x_label, std::string y_label, Point lo, Point hi, double width = 900.0);

  void polygon(const std::vector<Point>& corners, const std::string& fill, double opacity);
  void circle(Point centre, double radius, const std::string& fill, double opacity);
  /// Axis-aligned squares of edge `size` at `centres`, drawn as one path.
  void squares(const std::vector<Point>& centres, double size, const std::string& fill, double opacity);
  void polyline(const std::vector<Point>& points, const std::string& colour, double width_px, double opacity);
  /// A labelled point marker.
  void marker(Point at, const std::string& label, const std::string& colour);
  /// An entry of the legend under the title.
  void legend(const std::string& label, const std::string& colour);

  std::string svg() const;

private:
  double px(double x) const;
  double py(double y) const;

  std::string title_, x_label_, y_label_;
  Point lo_, hi_;
  double width_, height_, scale_;
  std::string body_;
  std::vector<std::pair<std::string, std::string>> legend_;
};

/// A timeline: lanes of labelled intervals and of instants over one time axis.
struct Interval {
  double from = 0.0;
  double to = 0.0;
  std::string label;
  std::string colour;
};
struct Instant {
  double at = 0.0;
  std::string label;
  std::string colour;
};
struct Lane {
  std::string name;
  std::vector<Interval> intervals;
  std::vector<Instant> instants;
};
std::string timelineSvg(const std::string& title, const std::string& x_label, double t_lo, double t_hi,
                        const std::vector<Lane>& lanes);

/// Horizontal bars: each row's value against its reference (drawn as a tick), both in `unit`.
struct Bar {
  std::string label;
  double value = 0.0;
  std::optional<double> reference;
};
std::string barChartSvg(const std::string& title, const std::string& unit, const std::vector<Bar>& bars,
                        const std::string& value_label = "measured", const std::string& reference_label = "contract");

/// A grid of cells over two sets of labels, each cell coloured by a value in [0, 1] (red at 0,
/// amber half way, green at 1) and carrying its text ("7/10"); a cell without a value is grey.
/// `values[row][column]`: rows along `row_labels` (top to bottom), columns along
/// `column_labels`; the texts likewise.
struct Heatmap {
  std::string title;
  std::string row_name;
  std::string column_name;
  std::vector<std::string> row_labels;
  std::vector<std::string> column_labels;
  std::vector<std::vector<std::optional<double>>> values;
  std::vector<std::vector<std::string>> texts;
};
std::string heatmapSvg(const Heatmap& map);

}  // namespace quad::report
