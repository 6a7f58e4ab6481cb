// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/estimate_plot.hpp"

#include <functional>

#include "quad/common/xml_text.hpp"
#include "quad/report/chart.hpp"

namespace quad::launch {

namespace {

report::Series line(const std::vector<EstimateErrorPoint>& series, const std::function<double(const EstimateErrorPoint&)>& value,
                    const char* colour, const char* dash, const char* label)
{
  report::Series s;
  s.colour = colour;
  s.dash = dash;
  s.label = label;
  s.points.reserve(series.size());
  for (const auto& p : series) {
    s.points.emplace_back(p.t_s, value(p));
  }
  return s;
}

}  // namespace

std::string estimateErrorSvg(const std::vector<EstimateErrorPoint>& series, const std::string& title)
{
  if (series.size() < 2) {
    return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"820\" height=\"100\" font-family=\"sans-serif\">\n"
           "<text x=\"20\" y=\"22\" font-size=\"15\">" +
           common::xmlEscaped(title) +
           "</text>\n<text x=\"20\" y=\"60\" font-size=\"13\">fewer than two scored estimates: nothing to draw</text>\n</svg>\n";
  }
  report::Panel position{"position [m]", {}, 0.0, {}};
  position.series.push_back(line(series, [](const EstimateErrorPoint& p) { return p.position_m; }, "#1f5fbf", "", "position error"));
  position.series.push_back(line(series, [](const EstimateErrorPoint& p) { return p.position_3sigma_m; }, "#999", "5,3",
                                 "the estimate's 3-sigma"));
  report::Panel angles{"angle [deg]", {}, 0.0, {}};
  angles.series.push_back(line(series, [](const EstimateErrorPoint& p) { return p.attitude_deg; }, "#c0392b", "", "attitude error"));
  angles.series.push_back(line(series, [](const EstimateErrorPoint& p) { return p.yaw_deg; }, "#27864a", "",
                               "heading error (signed)"));
  return report::stackedChartSvg(title, "sim time [s]", {position, angles});
}

}  // namespace quad::launch
