// SPDX-License-Identifier: BSD-3-Clause
#include "quad/campaign/campaign_report.hpp"

#include <algorithm>
#include <fstream>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "quad/common/xml_text.hpp"
#include "quad/report/chart.hpp"
#include "quad/report/page.hpp"

namespace quad::campaign {

namespace fs = std::filesystem;

namespace {

std::string esc(const std::string& text) { return common::xmlEscaped(text); }

/// One way the runs vary: the worlds, an axis, the seeds; its values in the campaign's order.
struct Dimension {
  std::string name;
  std::vector<std::string> values;
  std::function<std::string(const CampaignRun&)> of;
};

std::vector<Dimension> dimensions(const std::vector<CampaignRun>& runs, const std::vector<Axis>& axes)
{
  std::vector<Dimension> out;
  const auto distinct = [&](const std::function<std::string(const CampaignRun&)>& of) {
    std::vector<std::string> values;
    for (const CampaignRun& r : runs) {
      if (std::find(values.begin(), values.end(), of(r)) == values.end()) {
        values.push_back(of(r));
      }
    }
    return values;
  };
  const auto world = [](const CampaignRun& r) { return r.world; };
  out.push_back({"world", distinct(world), world});
  const std::vector<std::string> labels = axisLabels(axes);
  for (std::size_t i = 0; i < axes.size(); ++i) {
    const std::string key = axes[i].key;
    out.push_back({labels[i], axes[i].values, [key](const CampaignRun& r) { return r.param(key); }});
  }
  const auto seed = [](const CampaignRun& r) { return std::to_string(r.seed); };
  out.push_back({"seed", distinct(seed), seed});
  std::erase_if(out, [](const Dimension& d) { return d.values.size() < 2; });
  return out;
}

/// The success rate over two dimensions (or one, in a single row), the others pooled.
report::Heatmap successMap(const std::vector<CampaignRun>& runs, const Dimension& rows,
                           const std::optional<Dimension>& columns)
{
  report::Heatmap map;
  map.row_name = rows.name;
  map.row_labels = rows.values;
  map.column_name = columns ? columns->name : "";
  map.column_labels = columns ? columns->values : std::vector<std::string>{"all"};
  map.title = columns ? fmt::format("Success rate: {} x {}", rows.name, columns->name)
                      : fmt::format("Success rate by {}", rows.name);
  for (const std::string& rv : map.row_labels) {
    std::vector<std::optional<double>> values;
    std::vector<std::string> texts;
    for (const std::string& cv : map.column_labels) {
      int n = 0;
      int ok = 0;
      for (const CampaignRun& r : runs) {
        if (rows.of(r) == rv && (!columns || columns->of(r) == cv)) {
          ++n;
          ok += r.success ? 1 : 0;
        }
      }
      values.push_back(n > 0 ? std::optional<double>(static_cast<double>(ok) / n) : std::nullopt);
      texts.push_back(n > 0 ? fmt::format("{}/{}", ok, n) : "-");
    }
    map.values.push_back(std::move(values));
    map.texts.push_back(std::move(texts));
  }
  return map;
}

/// The runs' values of one figure as an empirical distribution: the fraction of runs at or
/// below each value.
std::string distributionSvg(const std::vector<CampaignRun>& runs, const std::string& title, const std::string& unit,
                            const std::function<std::optional<double>(const CampaignRun&)>& of)
{
  std::vector<double> values;
  for (const CampaignRun& r : runs) {
    if (const auto v = of(r)) {
      values.push_back(*v);
    }
  }
  std::sort(values.begin(), values.end());
  report::Series s;
  s.style = report::Series::Style::kSteps;
  s.label = fmt::format("{} runs", values.size());
  if (!values.empty()) {
    s.points.emplace_back(values.front(), 0.0);  // the step up to the first run
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    s.points.emplace_back(values[i], static_cast<double>(i + 1) / static_cast<double>(values.size()));
  }
  report::Panel panel{"fraction of runs at or below", {s}, 0.0, 1.0};
  return report::stackedChartSvg(title, unit, {panel});
}

void writeFile(const fs::path& file, const std::string& text)
{
  std::ofstream out(file, std::ios::binary);
  out << text;
  out.close();
  if (!out) {
    throw std::runtime_error(file.string() + ": cannot write");
  }
}

std::string number(const std::optional<double>& v, const char* format)
{
  return v ? fmt::format(fmt::runtime(format), *v) : "-";
}

std::string table(const std::vector<CampaignRun>& runs, const std::vector<Axis>& axes, const fs::path& dir)
{
  std::string html = "<table>\n<tr><th>run</th><th>world</th>";
  for (const std::string& label : axisLabels(axes)) {
    html += "<th>" + esc(label) + "</th>";
  }
  html += "<th>seed</th><th>result</th><th>collisions</th><th>flown/opt</th><th>closest m</th><th>to goal s</th>"
          "<th>avg m/s</th><th>top m/s</th><th>wall s</th><th>failure</th></tr>\n";
  for (const CampaignRun& r : runs) {
    const fs::path report = fs::path(r.name) / "run" / "report.html";
    const std::string name = fs::exists(dir / report)
                                 ? fmt::format("<a href=\"{}\">{}</a>", esc(report.generic_string()), esc(r.name))
                                 : esc(r.name);
    html += fmt::format("<tr{}><td>{}</td><td>{}</td>", r.success ? "" : " class=\"failed\"", name, esc(r.world));
    for (const Axis& a : axes) {
      const std::string value = r.param(a.key);
      html += "<td>" + esc(value.empty() ? "-" : value) + "</td>";
    }
    html += fmt::format("<td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.2f}</td><td>{}</td><td>{}</td><td>{:.1f}</td>"
                        "<td>{:.1f}</td><td>{}</td></tr>\n",
                        r.seed, r.success ? "ok" : esc(r.end.empty() ? "error" : r.end), r.collisions,
                        number(r.flown_over_optimum, "{:.3f}"), r.min_clearance_m, number(r.time_to_goal_s, "{:.1f}"),
                        number(r.average_speed_mps, "{:.1f}"), r.top_speed_mps, r.wall_s, esc(r.failure));
  }
  return html + "</table>\n";
}

}  // namespace

fs::path writeCampaignReport(const std::vector<CampaignRun>& runs, const std::vector<Axis>& axes, const fs::path& dir)
{
  const int ok = static_cast<int>(std::count_if(runs.begin(), runs.end(), [](const CampaignRun& r) { return r.success; }));
  std::vector<std::pair<std::string, std::string>> figures;  // file, caption
  const auto figure = [&](const std::string& file, const std::string& caption, const std::string& svg) {
    writeFile(dir / file, svg);
    figures.emplace_back(file, caption);
  };
  const std::vector<Dimension> dims = dimensions(runs, axes);
  constexpr std::size_t kMostMaps = 6;
  if (dims.size() == 1) {
    figure("campaign_success_0.svg", "success rate by " + dims[0].name, report::heatmapSvg(successMap(runs, dims[0], {})));
  }
  for (std::size_t i = 0; i < dims.size(); ++i) {
    for (std::size_t j = i + 1; j < dims.size() && figures.size() < kMostMaps; ++j) {
      figure(fmt::format("campaign_success_{}.svg", figures.size()),
             fmt::format("success rate over {} and {}, the other dimensions pooled", dims[i].name, dims[j].name),
             report::heatmapSvg(successMap(runs, dims[i], dims[j])));
    }
  }
  figure("campaign_flown_over_optimum.svg", "flown length over the known-map optimum, every run that has one",
         distributionSvg(runs, "Flown length over the known-map optimum", "flown / optimum",
                         [](const CampaignRun& r) { return r.flown_over_optimum; }));
  figure("campaign_closest_approach.svg", "closest approach to an obstacle, every run",
         distributionSvg(runs, "Closest approach", "m",
                         [](const CampaignRun& r) { return std::optional<double>(r.min_clearance_m); }));
  figure("campaign_time_to_goal.svg", "time to the goal from the mission's start, every run that reached it",
         distributionSvg(runs, "Time to the goal", "s (sim)", [](const CampaignRun& r) { return r.time_to_goal_s; }));

  std::string html = report::pageHead("quad campaign: " + dir.filename().string(),
                              "body { max-width: 1100px; }\ntr.failed td { color: #c0392b; }\n");
  html += fmt::format("<p><b>{} of {} runs succeeded</b>{}.</p>\n", ok, runs.size(),
                      ok == static_cast<int>(runs.size()) ? "" : "; each failed run in red, linked to its report");
  html += "<h2>Success</h2>\n";
  for (const auto& [file, caption] : figures) {
    if (file.starts_with("campaign_success")) {
      html += report::figureElement(file, caption);
    }
  }
  html += "<h2>Runs</h2>\n" + table(runs, axes, dir) + "<h2>Distributions</h2>\n";
  for (const auto& [file, caption] : figures) {
    if (!file.starts_with("campaign_success")) {
      html += report::figureElement(file, caption);
    }
  }
  html += "</body>\n</html>\n";
  const fs::path page = dir / "campaign.html";
  writeFile(page, html);
  return page;
}

}  // namespace quad::campaign
