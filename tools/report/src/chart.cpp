// SPDX-License-Identifier: BSD-3-Clause
#include "quad/report/chart.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "quad/common/xml_text.hpp"

namespace quad::report {

namespace {

constexpr double kWidth = 900.0;
constexpr double kLeft = 80.0;   // room for the value labels
constexpr double kRight = 20.0;
constexpr double kTop = 50.0;    // room for the title
constexpr int kTicks = 5;        // about this many labelled ticks on an axis
constexpr int kMaxTicks = 60;    // never more (a log axis spans at most this many decades)

std::string esc(const std::string& text) { return common::xmlEscaped(text); }

std::string header(double width, double height, const std::string& title)
{
  return fmt::format(R"(<svg xmlns="http://www.w3.org/2000/svg" width="{:.0f}" height="{:.0f}" )"
                     R"(viewBox="0 0 {:.0f} {:.0f}" font-family="sans-serif">)"
                     "\n"
                     R"(<rect width="100%" height="100%" fill="white"/>)"
                     "\n"
                     R"(<text x="{:.1f}" y="22" font-size="15" text-anchor="middle">{}</text>)"
                     "\n",
                     width, height, width, height, width / 2.0, esc(title));
}

std::string legendEntry(double x, double y, const std::string& colour, const std::string& dash, const std::string& label)
{
  return fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="{}" stroke-width="3" stroke-dasharray="{}"/>)"
                     R"(<text x="{:.1f}" y="{:.1f}" font-size="12">{}</text>)"
                     "\n",
                     x, y - 4.0, x + 20.0, y - 4.0, colour, dash, x + 26.0, y, esc(label));
}

/// Width of a legend entry: its line and its text at about 6.5 px a character.
double legendWidth(const std::string& label) { return 40.0 + 6.5 * static_cast<double>(label.size()); }

bool finite(const Point& p) { return std::isfinite(p.first) && std::isfinite(p.second); }

}  // namespace

std::vector<double> ticks(const Axis& a)
{
  std::vector<double> out;
  if (!std::isfinite(a.lo) || !std::isfinite(a.hi) || !(a.step > 0.0)) {
    return out;
  }
  for (int k = 0; k <= kMaxTicks; ++k) {
    const double v = a.lo + k * a.step;
    if (v > a.hi + a.step * 1e-6) {
      break;
    }
    out.push_back(std::abs(v) < a.step * 1e-9 ? 0.0 : v);
  }
  return out;
}

Axis axisOver(double lo, double hi)
{
  if (!std::isfinite(lo) || !std::isfinite(hi)) {
    lo = 0.0;
    hi = 1.0;
  }
  if (!(hi > lo)) {
    hi = lo + 1.0;
  }
  const double raw = (hi - lo) / kTicks;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * power;
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * power >= raw) {
      step = m * power;
      break;
    }
  }
  return {std::floor(lo / step) * step, std::ceil(hi / step) * step, step};
}

// ---------------------------------------------------------------------------------------------
// Stacked panels

namespace {

constexpr double kPanelHeight = 190.0;
constexpr double kGap = 62.0;  // between panels: the time labels above, the legend below

class PanelFrame {
public:
  PanelFrame(double top, Axis x, Axis y, bool log) : top_(top), x_(x), y_(y), log_(log) {}

  double x(double v) const { return kLeft + (v - x_.lo) / (x_.hi - x_.lo) * (kWidth - kLeft - kRight); }
  double y(double v) const
  {
    const double u = std::clamp(log_ ? std::log10(v) : v, y_.lo, y_.hi);
    return top_ + kPanelHeight - (u - y_.lo) / (y_.hi - y_.lo) * kPanelHeight;
  }

  std::string frame(const std::string& unit) const
  {
    std::string out = fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="none" stroke="#444"/>)"
                                  "\n",
                                  kLeft, top_, kWidth - kLeft - kRight, kPanelHeight);
    for (const double u : ticks(y_)) {
      const double v = log_ ? std::pow(10.0, u) : u;
      const double at = y(log_ ? v : u);
      out += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#ddd"/>)"
                         R"(<text x="{:.1f}" y="{:.1f}" text-anchor="end" font-size="11">{:g}</text>)"
                         "\n",
                         kLeft, at, kWidth - kRight, at, kLeft - 6.0, at + 4.0, v);
    }
    for (const double t : ticks(x_)) {
      out += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle" font-size="11">{:g}</text>)"
                         "\n",
                         x(t), top_ + kPanelHeight + 15.0, t);
    }
    out += fmt::format(R"svg(<text x="16" y="{:.1f}" font-size="12" transform="rotate(-90 16 {:.1f})" text-anchor="middle">{}</text>)svg"
                       "\n",
                       top_ + kPanelHeight / 2.0, top_ + kPanelHeight / 2.0, esc(unit));
    return out;
  }

  std::string draw(const Series& s) const
  {
    std::string points;
    std::string dots;
    double previous_y = std::numeric_limits<double>::quiet_NaN();
    for (const Point& p : s.points) {
      if (!finite(p) || (log_ && p.second <= 0.0)) {
        continue;
      }
      const double px = x(p.first);
      const double py = y(p.second);
      if (s.style == Series::Style::kDots) {
        dots += fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="2.2"/>)", px, py);
        continue;
      }
      if (s.style == Series::Style::kSteps && std::isfinite(previous_y)) {
        points += fmt::format("{:.1f},{:.1f} ", px, previous_y);
      }
      points += fmt::format("{:.1f},{:.1f} ", px, py);
      previous_y = py;
    }
    if (s.style == Series::Style::kDots) {
      return fmt::format(R"(<g fill="{}">{}</g>)"
                         "\n",
                         s.colour, dots);
    }
    return fmt::format(R"(<polyline fill="none" stroke="{}" stroke-width="1.3" stroke-dasharray="{}" points="{}"/>)"
                       "\n",
                       s.colour, s.dash, points);
  }

  double top() const { return top_; }

private:
  double top_;
  Axis x_;
  Axis y_;
  bool log_;
};

}  // namespace

std::string stackedChartSvg(const std::string& title, const std::string& x_label, const std::vector<Panel>& panels)
{
  double x_lo = std::numeric_limits<double>::infinity();
  double x_hi = -x_lo;
  for (const Panel& panel : panels) {
    for (const Series& s : panel.series) {
      for (const Point& p : s.points) {
        if (finite(p)) {
          x_lo = std::min(x_lo, p.first);
          x_hi = std::max(x_hi, p.first);
        }
      }
    }
  }
  const Axis x_axis = axisOver(x_lo, x_hi);
  const double height = kTop + static_cast<double>(panels.size()) * (kPanelHeight + kGap) + 10.0;
  std::string svg = header(kWidth, height, title);
  double top = kTop;
  for (const Panel& panel : panels) {
    double lo = panel.lo.value_or(std::numeric_limits<double>::infinity());
    double hi = panel.hi.value_or(-std::numeric_limits<double>::infinity());
    bool any = false;
    for (const Series& s : panel.series) {
      for (const Point& p : s.points) {
        if (!finite(p) || (panel.log_scale && p.second <= 0.0)) {
          continue;
        }
        const double v = panel.log_scale ? std::log10(p.second) : p.second;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        any = true;
      }
    }
    Axis y_axis = axisOver(lo, hi);
    if (panel.log_scale && any) {  // whole decades
      y_axis = {std::floor(lo), std::max(std::ceil(hi), std::floor(lo) + 1.0), 1.0};
    }
    const PanelFrame frame(top, x_axis, y_axis, panel.log_scale);
    svg += frame.frame(panel.unit);
    if (!any) {
      svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="13" text-anchor="middle" fill="#666">no data</text>)"
                         "\n",
                         (kLeft + kWidth - kRight) / 2.0, top + kPanelHeight / 2.0);
    }
    double legend_x = kLeft + 10.0;
    for (const Series& s : panel.series) {
      svg += frame.draw(s);
      if (!s.label.empty()) {
        svg += legendEntry(legend_x, top - 8.0, s.colour, s.dash, s.label);
        legend_x += legendWidth(s.label);
      }
    }
    top += kPanelHeight + kGap;
  }
  svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="12" text-anchor="middle">{}</text>)"
                     "\n</svg>\n",
                     kLeft + (kWidth - kLeft - kRight) / 2.0, top - kGap + 34.0, esc(x_label));
  return svg;
}

// ---------------------------------------------------------------------------------------------
// Plan views

namespace {
constexpr double kViewMargin = 60.0;  // around the drawing: axis labels and legend
constexpr double kLegendRoom = 18.0;  // a second line of legend
}

PlanView::PlanView(std::string title, std::string x_label, std::string y_label, Point lo, Point hi, double width)
    : title_(std::move(title)), x_label_(std::move(x_label)), y_label_(std::move(y_label)), lo_(lo), hi_(hi), width_(width)
{
  if (!(hi_.first > lo_.first)) {
    hi_.first = lo_.first + 1.0;
  }
  if (!(hi_.second > lo_.second)) {
    hi_.second = lo_.second + 1.0;
  }
  scale_ = (width_ - 2.0 * kViewMargin) / (hi_.first - lo_.first);
  height_ = (hi_.second - lo_.second) * scale_ + 2.0 * kViewMargin + 20.0 + kLegendRoom;
}

double PlanView::px(double x) const { return kViewMargin + (x - lo_.first) * scale_; }
double PlanView::py(double y) const { return kViewMargin + 20.0 + kLegendRoom + (hi_.second - y) * scale_; }

void PlanView::polygon(const std::vector<Point>& corners, const std::string& fill, double opacity)
{
  std::string points;
  for (const Point& c : corners) {
    points += fmt::format("{:.1f},{:.1f} ", px(c.first), py(c.second));
  }
  body_ += fmt::format(R"(<polygon points="{}" fill="{}" fill-opacity="{:.2f}"/>)"
                       "\n",
                       points, fill, opacity);
}

void PlanView::circle(Point centre, double radius, const std::string& fill, double opacity)
{
  body_ += fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="{:.1f}" fill="{}" fill-opacity="{:.2f}"/>)"
                       "\n",
                       px(centre.first), py(centre.second), std::max(radius * scale_, 0.5), fill, opacity);
}

void PlanView::squares(const std::vector<Point>& centres, double size, const std::string& fill, double opacity)
{
  if (centres.empty()) {
    return;
  }
  const double side = std::max(size * scale_, 0.6);
  std::string path;
  path.reserve(centres.size() * 32);
  for (const Point& c : centres) {
    path += fmt::format("M{:.1f} {:.1f}h{:.1f}v{:.1f}h{:.1f}z", px(c.first) - side / 2.0, py(c.second) - side / 2.0, side,
                        side, -side);
  }
  body_ += fmt::format(R"(<path d="{}" fill="{}" fill-opacity="{:.2f}"/>)"
                       "\n",
                       path, fill, opacity);
}

void PlanView::polyline(const std::vector<Point>& points, const std::string& colour, double width_px, double opacity)
{
  std::string text;
  for (const Point& p : points) {
    if (finite(p)) {
      text += fmt::format("{:.1f},{:.1f} ", px(p.first), py(p.second));
    }
  }
  body_ += fmt::format(R"(<polyline fill="none" stroke="{}" stroke-width="{:.1f}" stroke-opacity="{:.2f}" )"
                       R"(stroke-linejoin="round" points="{}"/>)"
                       "\n",
                       colour, width_px, opacity, text);
}

void PlanView::marker(Point at, const std::string& label, const std::string& colour)
{
  body_ += fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="6" fill="{}" stroke="black"/>)"
                       R"(<text x="{:.1f}" y="{:.1f}" font-size="13" font-weight="bold">{}</text>)"
                       "\n",
                       px(at.first), py(at.second), colour, px(at.first) + 9.0, py(at.second) - 8.0, esc(label));
}

void PlanView::legend(const std::string& label, const std::string& colour) { legend_.emplace_back(label, colour); }

std::string PlanView::svg() const
{
  std::string out = header(width_, height_, title_);
  double x = kViewMargin;
  double y = 46.0;
  for (const auto& [label, colour] : legend_) {
    if (x + legendWidth(label) > width_ && x > kViewMargin) {  // on to a second line
      x = kViewMargin;
      y += 18.0;
    }
    out += legendEntry(x, y, colour, "", label);
    x += legendWidth(label);
  }
  const double left = px(lo_.first);
  const double right = px(hi_.first);
  const double top = py(hi_.second);
  const double bottom = py(lo_.second);
  out += fmt::format(R"(<svg x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" viewBox="{:.1f} {:.1f} {:.1f} {:.1f}">)"
                     "\n",
                     left, top, right - left, bottom - top, left, top, right - left, bottom - top);
  out += body_;
  out += "</svg>\n";
  out += fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="none" stroke="#444"/>)"
                     "\n",
                     left, top, right - left, bottom - top);
  const Axis xs = axisOver(lo_.first, hi_.first);
  for (const double v : ticks(xs)) {
    if (v >= lo_.first - 1e-9 && v <= hi_.first + 1e-9) {
      out += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle" font-size="11">{:g}</text>)"
                         "\n",
                         px(v), bottom + 15.0, v);
    }
  }
  const Axis ys = axisOver(lo_.second, hi_.second);
  for (const double v : ticks(ys)) {
    if (v >= lo_.second - 1e-9 && v <= hi_.second + 1e-9) {
      out += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="end" font-size="11">{:g}</text>)"
                         "\n",
                         left - 6.0, py(v) + 4.0, v);
    }
  }
  out += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="12" text-anchor="middle">{}</text>)"
                     "\n",
                     (left + right) / 2.0, bottom + 34.0, esc(x_label_));
  out += fmt::format(R"svg(<text x="16" y="{:.1f}" font-size="12" transform="rotate(-90 16 {:.1f})" text-anchor="middle">{}</text>)svg"
                     "\n</svg>\n",
                     (top + bottom) / 2.0, (top + bottom) / 2.0, esc(y_label_));
  return out;
}

// ---------------------------------------------------------------------------------------------
// Timelines

namespace {
constexpr double kLaneHeight = 34.0;
constexpr double kLaneLeft = 150.0;  // room for the lane names
}

std::string timelineSvg(const std::string& title, const std::string& x_label, double t_lo, double t_hi,
                        const std::vector<Lane>& lanes)
{
  const Axis axis = axisOver(t_lo, t_hi);
  const double plot_width = kWidth - kLaneLeft - kRight;
  const auto x = [&](double t) { return kLaneLeft + (std::clamp(t, axis.lo, axis.hi) - axis.lo) / (axis.hi - axis.lo) * plot_width; };
  const double height = kTop + static_cast<double>(lanes.size()) * (kLaneHeight + 30.0) + 50.0;
  std::string svg = header(kWidth, height, title);
  double top = kTop;
  for (const Lane& lane : lanes) {
    svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="12" text-anchor="end">{}</text>)"
                       R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="#f4f4f4" stroke="#bbb"/>)"
                       "\n",
                       kLaneLeft - 8.0, top + kLaneHeight / 2.0 + 4.0, esc(lane.name), kLaneLeft, top, plot_width, kLaneHeight);
    for (const Interval& i : lane.intervals) {
      const double x0 = x(i.from);
      const double w = std::max(x(i.to) - x0, 0.8);
      svg += fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="{}"><title>{}: {:.2f} to {:.2f} s</title></rect>)"
                         "\n",
                         x0, top, w, kLaneHeight, i.colour, esc(i.label), i.from, i.to);
      if (w > 7.0 * static_cast<double>(i.label.size()) + 6.0) {
        svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="11" fill="white">{}</text>)"
                           "\n",
                           x0 + 3.0, top + kLaneHeight / 2.0 + 4.0, esc(i.label));
      }
    }
    // Labels on two rows under the lane; one that would overlap its row's last is left to the
    // marker's hover text.
    std::array<double, 2> row_end{-1e300, -1e300};
    for (std::size_t k = 0; k < lane.instants.size(); ++k) {
      const Instant& e = lane.instants[k];
      const double at = x(e.at);
      svg += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="{}" stroke-width="2"><title>{} at {:.2f} s</title></line>)"
                         "\n",
                         at, top, at, top + kLaneHeight, e.colour, esc(e.label), e.at);
      // Labels past the middle end at their instant, so that none runs off the figure.
      const bool right_half = at > kLaneLeft + plot_width / 2.0;
      const double width = 5.6 * static_cast<double>(e.label.size());
      const double from = right_half ? at - 2.0 - width : at + 2.0;
      const std::size_t row = from > row_end[0] ? 0 : (from > row_end[1] ? 1 : 2);
      if (row == 2) {
        continue;
      }
      row_end[row] = from + width + 6.0;
      svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="10" fill="{}" text-anchor="{}">{}</text>)"
                         "\n",
                         right_half ? at - 2.0 : at + 2.0, top + kLaneHeight + 12.0 + 10.0 * static_cast<double>(row), e.colour,
                         right_half ? "end" : "start", esc(e.label));
    }
    top += kLaneHeight + 30.0;
  }
  for (const double t : ticks(axis)) {
    svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle" font-size="11">{:g}</text>)"
                       "\n",
                       x(t), top + 6.0, t);
  }
  svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="12" text-anchor="middle">{}</text>)"
                     "\n</svg>\n",
                     kLaneLeft + plot_width / 2.0, top + 28.0, esc(x_label));
  return svg;
}

// ---------------------------------------------------------------------------------------------
// Bars

std::string barChartSvg(const std::string& title, const std::string& unit, const std::vector<Bar>& bars,
                        const std::string& value_label, const std::string& reference_label)
{
  constexpr double kRow = 22.0;
  constexpr double kNames = 260.0;
  double hi = 0.0;
  for (const Bar& b : bars) {
    hi = std::max({hi, std::isfinite(b.value) ? b.value : 0.0, b.reference.value_or(0.0)});
  }
  const Axis axis = axisOver(0.0, hi);
  const double plot_width = kWidth - kNames - kRight - 90.0;
  const auto x = [&](double v) { return kNames + std::clamp(v, 0.0, axis.hi) / axis.hi * plot_width; };
  const double height = kTop + static_cast<double>(bars.size()) * kRow + 60.0;
  std::string svg = header(kWidth, height, title);
  svg += legendEntry(kNames, 42.0, "#1f5fbf", "", value_label) +
         legendEntry(kNames + legendWidth(value_label), 42.0, "#c0392b", "", reference_label);
  double top = kTop;
  for (const Bar& b : bars) {
    const double value = std::isfinite(b.value) ? b.value : 0.0;
    svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="11" text-anchor="end">{}</text>)"
                       R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="#1f5fbf"/>)"
                       R"(<text x="{:.1f}" y="{:.1f}" font-size="11">{:.3g}</text>)"
                       "\n",
                       kNames - 8.0, top + kRow / 2.0 + 4.0, esc(b.label), kNames, top + 4.0, x(value) - kNames, kRow - 8.0,
                       x(std::max(value, b.reference.value_or(0.0))) + 6.0, top + kRow / 2.0 + 4.0, value);
    if (b.reference) {
      svg += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#c0392b" stroke-width="3"/>)"
                         "\n",
                         x(*b.reference), top + 1.0, x(*b.reference), top + kRow - 1.0);
    }
    top += kRow;
  }
  for (const double v : ticks(axis)) {
    svg += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#ddd"/>)"
                       R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle" font-size="11">{:g}</text>)"
                       "\n",
                       x(v), kTop, x(v), top, x(v), top + 15.0, v);
  }
  svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="12" text-anchor="middle">{}</text>)"
                     "\n</svg>\n",
                     kNames + plot_width / 2.0, top + 34.0, esc(unit));
  return svg;
}

namespace {
/// Red (0) through amber (0.5) to green (1).
std::string rateColour(double v)
{
  const double t = std::clamp(v, 0.0, 1.0);
  const auto mix = [](double a, double b, double f) { return static_cast<int>(std::lround(a + (b - a) * f)); };
  if (t < 0.5) {
    return fmt::format("#{:02x}{:02x}{:02x}", mix(0xc0, 0xf0, 2 * t), mix(0x39, 0xb4, 2 * t), mix(0x2b, 0x29, 2 * t));
  }
  return fmt::format("#{:02x}{:02x}{:02x}", mix(0xf0, 0x27, 2 * t - 1), mix(0xb4, 0x86, 2 * t - 1),
                     mix(0x29, 0x4a, 2 * t - 1));
}
}  // namespace

std::string heatmapSvg(const Heatmap& map)
{
  constexpr double kCellW = 80.0;
  constexpr double kCellH = 34.0;
  constexpr double kNames = 140.0;
  const double width = std::max(kNames + kCellW * static_cast<double>(map.column_labels.size()) + kRight, 360.0);
  const double height = kTop + 30.0 + kCellH * static_cast<double>(map.row_labels.size()) + 30.0;
  std::string svg = header(width, height, map.title);
  const double top = kTop + 30.0;
  svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="12" text-anchor="middle">{}</text>)"
                     "\n",
                     kNames + kCellW * static_cast<double>(map.column_labels.size()) / 2.0, kTop + 4.0,
                     esc(map.column_name));
  svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="12" text-anchor="end">{}</text>)"
                     "\n",
                     kNames - 8.0, kTop + 24.0, esc(map.row_name));
  for (std::size_t c = 0; c < map.column_labels.size(); ++c) {
    svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="11" text-anchor="middle">{}</text>)"
                       "\n",
                       kNames + kCellW * (static_cast<double>(c) + 0.5), top - 6.0, esc(map.column_labels[c]));
  }
  for (std::size_t r = 0; r < map.row_labels.size(); ++r) {
    const double y = top + kCellH * static_cast<double>(r);
    svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="11" text-anchor="end">{}</text>)"
                       "\n",
                       kNames - 8.0, y + kCellH / 2.0 + 4.0, esc(map.row_labels[r]));
    for (std::size_t c = 0; c < map.column_labels.size(); ++c) {
      const bool known = r < map.values.size() && c < map.values[r].size() && map.values[r][c].has_value();
      const double v = known ? map.values[r][c].value() : std::numeric_limits<double>::quiet_NaN();
      const std::string text = r < map.texts.size() && c < map.texts[r].size() ? map.texts[r][c] : "";
      const double x = kNames + kCellW * static_cast<double>(c);
      svg += fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="{}" stroke="white"/>)"
                         R"(<text x="{:.1f}" y="{:.1f}" font-size="12" text-anchor="middle">{}</text>)"
                         "\n",
                         x, y, kCellW, kCellH, std::isfinite(v) ? rateColour(v) : "#dddddd", x + kCellW / 2.0,
                         y + kCellH / 2.0 + 4.0, esc(text));
    }
  }
  return svg + "</svg>\n";
}

}  // namespace quad::report
