// SPDX-License-Identifier: BSD-3-Clause
// The SVG figures: round axes, every point drawn, one scale on both axes of a view.
#include "quad/report/chart.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>

#include "occurrences.hpp"

namespace quad::report {
namespace {

using test::occurrences;

TEST(Axis, SpansItsValuesWithAboutFiveRoundTicks)
{
  for (const auto& [lo, hi] : {std::pair{0.0, 1.0}, {-3.7, 12.2}, {0.013, 0.0191}, {1e5, 3.3e5}, {-2.0, -1.5}}) {
    const Axis a = axisOver(lo, hi);
    EXPECT_LE(a.lo, lo);
    EXPECT_GE(a.hi, hi);
    const double ticks = (a.hi - a.lo) / a.step;
    EXPECT_GE(ticks, 2.5) << lo << " " << hi;
    EXPECT_LE(ticks, 11.0) << lo << " " << hi;
    const double mantissa = a.step / std::pow(10.0, std::floor(std::log10(a.step)));
    EXPECT_TRUE(std::abs(mantissa - 1.0) < 1e-9 || std::abs(mantissa - 2.0) < 1e-9 || std::abs(mantissa - 5.0) < 1e-9);
  }
  const Axis flat = axisOver(2.0, 2.0);
  EXPECT_GT(flat.hi, flat.lo);
  const Axis bad = axisOver(NAN, 1.0);
  EXPECT_TRUE(std::isfinite(bad.lo) && std::isfinite(bad.hi));
}

TEST(StackedChart, DrawsEveryPointOfEverySeriesAndSaysWhenAPanelIsEmpty)
{
  Series line{{}, "#123456", "a <line>"};
  Series dots{{}, "#654321", "dots"};
  dots.style = Series::Style::kDots;
  for (int k = 0; k < 30; ++k) {
    line.points.emplace_back(0.1 * k, std::sin(0.1 * k));
    dots.points.emplace_back(0.1 * k, 1.0 + k);
  }
  line.points.emplace_back(3.0, NAN);  // left out, never drawn as "nan"
  const std::string svg = stackedChartSvg("title & more", "t [s]", {{"one", {line}, {}, {}}, {"two", {dots}, {}, {}}, {"three", {}, {}, {}}});
  EXPECT_EQ(svg.rfind("<svg ", 0), 0U);
  EXPECT_NE(svg.find("title &amp; more"), std::string::npos);
  EXPECT_NE(svg.find("a &lt;line&gt;"), std::string::npos);
  EXPECT_EQ(occurrences(svg, "<polyline"), 1);
  EXPECT_EQ(occurrences(svg, "<circle"), 30);
  EXPECT_EQ(occurrences(svg, "no data"), 1);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  const auto at = svg.find("points=\"");
  const std::string points = svg.substr(at + 8, svg.find('"', at + 8) - at - 8);
  EXPECT_EQ(occurrences(points, ","), 30);
}

TEST(StackedChart, AnEmptyLogPanelSaysSoWithFiniteTicks)
{
  Panel empty{"count", {Series{}}, {}, {}};
  empty.log_scale = true;
  const std::string svg = stackedChartSvg("t", "x", {empty});
  EXPECT_NE(svg.find("no data"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
  EXPECT_LE(occurrences(svg, "<text"), 40);
  EXPECT_TRUE(ticks({INFINITY, INFINITY, 1.0}).empty());
  EXPECT_LE(ticks({0.0, 1e9, 1e-9}).size(), 61U);
}

TEST(StackedChart, StepsHoldEachValueUntilTheNext)
{
  Series steps{{{0.0, 1.0}, {1.0, 2.0}, {2.0, 3.0}}, "#000", "s"};
  steps.style = Series::Style::kSteps;
  const std::string svg = stackedChartSvg("t", "x", {{"v", {steps}, {}, {}}});
  const auto at = svg.find("points=\"");
  const std::string points = svg.substr(at + 8, svg.find('"', at + 8) - at - 8);
  EXPECT_EQ(occurrences(points, ","), 5);  // a corner before each new value
}

TEST(PlanView, KeepsOneScaleOnBothAxes)
{
  PlanView v("view", "x", "y", {0.0, 0.0}, {40.0, 10.0}, 900.0);
  v.squares({{5.0, 5.0}}, 1.0, "#000", 1.0);
  const std::string svg = v.svg();
  // 780 px for 40 m: 19.5 px a metre; the drawing is 10 m high, so 195 px.
  const std::regex inner(R"re(<svg x="[0-9.]+" y="[0-9.]+" width="([0-9.]+)" height="([0-9.]+)")re");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, inner));
  EXPECT_NEAR(std::stod(m[1]), 780.0, 0.2);
  EXPECT_NEAR(std::stod(m[2]), 195.0, 0.2);
  EXPECT_NE(svg.find("h19.5v19.5h-19.5z"), std::string::npos);  // a 1 m square is square
}

TEST(Timeline, DrawsIntervalsAndInstantsInTheirLanes)
{
  const std::string svg = timelineSvg("modes", "t", 0.0, 10.0,
                                      {{"mode", {{0.0, 4.0, "takeoff", "#111"}, {4.0, 10.0, "mission", "#222"}}, {}},
                                       {"events", {}, {{5.0, "collision", "#f00"}}}});
  EXPECT_EQ(occurrences(svg, "fill=\"#111\""), 1);
  EXPECT_EQ(occurrences(svg, "fill=\"#222\""), 1);
  EXPECT_NE(svg.find("collision at 5.00 s"), std::string::npos);
}

TEST(BarChart, DrawsAReferenceTickOnlyWhereThereIsOne)
{
  const std::string svg = barChartSvg("rates", "Hz", {{"a", 240.0, 250.0}, {"b", 9.0, std::nullopt}});
  EXPECT_EQ(occurrences(svg, "fill=\"#1f5fbf\"/>"), 2);
  EXPECT_EQ(occurrences(svg, "stroke=\"#c0392b\" stroke-width=\"3\"/>"), 1);
}

}  // namespace
}  // namespace quad::report
