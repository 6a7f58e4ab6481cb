// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/estimate_plot.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include <fmt/format.h>

#include "quad/common/xml_text.hpp"

namespace quad::launch {

namespace {

constexpr double kWidth = 820.0;
constexpr double kLeft = 70.0;    // room for the value labels
constexpr double kRight = 20.0;
constexpr double kPanelHeight = 200.0;
constexpr double kTop = 50.0;     // room for the title
constexpr double kGap = 60.0;     // between the panels: the first one's time labels, the second's legend
constexpr int kTicks = 5;         // about this many labelled ticks on an axis

/// A round step (1, 2 or 5 times a power of ten) giving about kTicks ticks over `span`.
double tickStep(double span)
{
  const double raw = span / kTicks;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * power >= raw) {
      return m * power;
    }
  }
  return 10.0 * power;
}

struct Axis {
  double lo;
  double hi;
  double step;
};

/// `lo`..`hi` widened to whole ticks (a flat series gets a span of 1).
Axis axisOver(double lo, double hi)
{
  if (!(hi > lo)) {
    hi = lo + 1.0;
  }
  const double step = tickStep(hi - lo);
  return {std::floor(lo / step) * step, std::ceil(hi / step) * step, step};
}

struct Line {
  std::function<double(const EstimateErrorPoint&)> value;
  const char* colour;
  const char* dash;  // stroke-dasharray, "" for solid
  const char* label;
};

class Panel {
public:
  Panel(double top, Axis time, Axis values) : top_(top), time_(time), values_(values) {}

  double x(double t) const { return kLeft + (t - time_.lo) / (time_.hi - time_.lo) * (kWidth - kLeft - kRight); }
  double y(double v) const { return top_ + kPanelHeight - (v - values_.lo) / (values_.hi - values_.lo) * kPanelHeight; }

  std::string frame(const std::string& unit) const
  {
    std::string out = fmt::format(
        R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="none" stroke="#444"/>)"
        "\n",
        kLeft, top_, kWidth - kLeft - kRight, kPanelHeight);
    for (double v = values_.lo; v <= values_.hi + values_.step * 1e-6; v += values_.step) {
      out += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#ddd"/>)"
                         R"(<text x="{:.1f}" y="{:.1f}" text-anchor="end" font-size="11">{:g}</text>)"
                         "\n",
                         kLeft, y(v), kWidth - kRight, y(v), kLeft - 6.0, y(v) + 4.0, std::abs(v) < 1e-12 ? 0.0 : v);
    }
    for (double t = time_.lo; t <= time_.hi + time_.step * 1e-6; t += time_.step) {
      out += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle" font-size="11">{:g}</text>)"
                         "\n",
                         x(t), top_ + kPanelHeight + 15.0, t);
    }
    out += fmt::format(
        R"svg(<text x="16" y="{:.1f}" font-size="12" transform="rotate(-90 16 {:.1f})" text-anchor="middle">{}</text>)svg"
        "\n",
        top_ + kPanelHeight / 2.0, top_ + kPanelHeight / 2.0, common::xmlEscaped(unit));
    return out;
  }

  std::string line(const std::vector<EstimateErrorPoint>& series, const Line& l, int index) const
  {
    std::string points;
    for (const auto& p : series) {
      points += fmt::format("{:.1f},{:.1f} ", x(p.t_s), y(std::clamp(l.value(p), values_.lo, values_.hi)));
    }
    const double lx = kLeft + 10.0 + 190.0 * index;
    const double ly = top_ - 8.0;
    return fmt::format(R"(<polyline fill="none" stroke="{}" stroke-width="1.3" stroke-dasharray="{}" points="{}"/>)"
                       "\n"
                       R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="{}" stroke-width="2" stroke-dasharray="{}"/>)"
                       R"(<text x="{:.1f}" y="{:.1f}" font-size="12">{}</text>)"
                       "\n",
                       l.colour, l.dash, points, lx, ly - 4.0, lx + 20.0, ly - 4.0, l.colour, l.dash, lx + 26.0, ly,
                       common::xmlEscaped(l.label));
  }

private:
  double top_;
  Axis time_;
  Axis values_;
};

}  // namespace

std::string estimateErrorSvg(const std::vector<EstimateErrorPoint>& series, const std::string& title)
{
  const double height = kTop + 2.0 * kPanelHeight + kGap + 40.0;
  std::string svg = fmt::format(
      R"(<svg xmlns="http://www.w3.org/2000/svg" width="{:.0f}" height="{:.0f}" font-family="sans-serif">)"
      "\n"
      R"(<rect width="100%" height="100%" fill="white"/>)"
      "\n"
      R"(<text x="{:.1f}" y="22" font-size="15" text-anchor="middle">{}</text>)"
      "\n",
      kWidth, height, kWidth / 2.0, common::xmlEscaped(title));
  if (series.size() < 2) {
    return svg + R"(<text x="20" y="80" font-size="13">fewer than two scored estimates: nothing to draw</text>)"
                 "\n</svg>\n";
  }
  const Axis time = axisOver(series.front().t_s, series.back().t_s);
  double position_hi = 0.0;
  double angle_lo = 0.0;
  double angle_hi = 0.0;
  for (const auto& p : series) {
    position_hi = std::max({position_hi, p.position_m, p.position_3sigma_m});
    angle_lo = std::min(angle_lo, p.yaw_deg);
    angle_hi = std::max({angle_hi, p.attitude_deg, p.yaw_deg});
  }
  const Panel position(kTop, time, axisOver(0.0, position_hi));
  svg += position.frame("position [m]");
  svg += position.line(series, {[](const EstimateErrorPoint& p) { return p.position_3sigma_m; }, "#999", "5,3",
                                "the estimate's 3-sigma"}, 1);
  svg += position.line(series, {[](const EstimateErrorPoint& p) { return p.position_m; }, "#1f5fbf", "",
                                "position error"}, 0);
  const Panel angles(kTop + kPanelHeight + kGap, time, axisOver(angle_lo, angle_hi));
  svg += angles.frame("angle [deg]");
  svg += angles.line(series, {[](const EstimateErrorPoint& p) { return p.attitude_deg; }, "#c0392b", "",
                              "attitude error"}, 0);
  svg += angles.line(series, {[](const EstimateErrorPoint& p) { return p.yaw_deg; }, "#27864a", "",
                              "heading error (signed)"}, 1);
  svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="12" text-anchor="middle">sim time [s]</text>)"
                     "\n</svg>\n",
                     kLeft + (kWidth - kLeft - kRight) / 2.0, height - 6.0);
  return svg;
}

}  // namespace quad::launch
