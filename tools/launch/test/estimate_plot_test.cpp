// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/estimate_plot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "occurrences.hpp"

namespace quad::launch {
namespace {

using test::occurrences;

TEST(EstimateErrorSvg, EverySeriesPointIsDrawnOnBothPanelsUnderItsTitle)
{
  std::vector<EstimateErrorPoint> series;
  for (int k = 0; k < 50; ++k) {
    const double t = 0.1 * k;
    series.push_back({t, 0.02 + 0.01 * std::sin(t), 0.06, 0.5, -0.3 + 0.1 * t});
  }
  const std::string svg = estimateErrorSvg(series, "demo <forest> & co");
  EXPECT_EQ(svg.rfind("<svg ", 0), 0U);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_NE(svg.find("demo &lt;forest&gt; &amp; co"), std::string::npos);  // escaped
  EXPECT_EQ(occurrences(svg, "<polyline"), 4);  // position, 3-sigma, attitude, heading
  // Each line has a point per sample: 4 lines of 50.
  const auto polyline = svg.find("points=\"");
  ASSERT_NE(polyline, std::string::npos);
  const std::string points = svg.substr(polyline + 8, svg.find('"', polyline + 8) - polyline - 8);
  EXPECT_EQ(occurrences(points, ","), 50);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

TEST(EstimateErrorSvg, TooShortASeriesSaysSo)
{
  const std::string svg = estimateErrorSvg({{1.0, 0.1, 0.2, 0.3, 0.4}}, "t");
  EXPECT_NE(svg.find("nothing to draw"), std::string::npos);
  EXPECT_EQ(occurrences(svg, "<polyline"), 0);
}

}  // namespace
}  // namespace quad::launch
