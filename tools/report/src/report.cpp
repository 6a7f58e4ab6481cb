// SPDX-License-Identifier: BSD-3-Clause
#include "quad/report/report.hpp"

#include <fstream>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "quad/bag/mcap.hpp"
#include "quad/common/xml_text.hpp"
#include "quad/report/figures.hpp"
#include "quad/report/page.hpp"
#include "quad/world/world_file.hpp"

namespace quad::report {

namespace fs = std::filesystem;

namespace {

using Json = nlohmann::ordered_json;

std::string esc(const std::string& text) { return common::xmlEscaped(text); }

/// A JSON file of the run's folder, or nothing when it is not there. One that does not parse
/// is a ReportError naming it.
std::optional<Json> readJson(const fs::path& file)
{
  std::ifstream in(file);
  if (!in) {
    return std::nullopt;
  }
  try {
    return Json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw ReportError(fmt::format("{}: not JSON: {}", file.string(), e.what()));
  }
}

std::string cell(const Json& v)
{
  if (v.is_null()) {
    return "-";
  }
  if (v.is_string()) {
    return v.get<std::string>();
  }
  if (v.is_number_float()) {
    return fmt::format("{:.4g}", v.get<double>());
  }
  if (v.is_array()) {
    std::string out;
    for (const auto& e : v) {
      out += (out.empty() ? "" : ", ") + cell(e);
    }
    return out;
  }
  return v.dump();
}

/// summary.json as table rows: nested objects' members under dotted names, a list of objects'
/// under its name and index (estimate.by_speed[0].samples).
void rows(const Json& j, const std::string& prefix, std::string& out)
{
  for (const auto& [key, value] : j.items()) {
    const std::string name = prefix.empty() ? key : prefix + "." + key;
    if (value.is_object()) {
      rows(value, name, out);
    } else if (value.is_array() && !value.empty() && value.front().is_object()) {
      for (std::size_t i = 0; i < value.size(); ++i) {
        rows(value[i], fmt::format("{}[{}]", name, i), out);
      }
    } else {
      out += fmt::format("<tr><th>{}</th><td>{}</td></tr>\n", esc(name), esc(cell(value)));
    }
  }
}

/// The headline: what a reader asks of a run first, from the summary's keys that it has.
std::string headline(const Json& summary)
{
  const auto number = [&](const char* key) -> std::optional<double> {
    return summary.contains(key) && summary[key].is_number() ? std::optional<double>(summary[key].get<double>())
                                                             : std::nullopt;
  };
  std::string rows_html;
  const auto row = [&](const std::string& name, const std::string& value) {
    rows_html += fmt::format("<tr><th>{}</th><td>{}</td></tr>\n", esc(name), value);
  };
  if (summary.contains("success") && summary["success"].is_boolean()) {
    const bool ok = summary["success"].get<bool>();
    std::string text = summary.value("outcome", std::string(ok ? "success" : "failed"));
    if (!ok && !summary.value("failure", std::string()).empty()) {
      text += ": " + summary["failure"].get<std::string>();
    }
    row("outcome", fmt::format("<b style=\"color:{}\">{}</b> {}", ok ? "#27864a" : "#c0392b", ok ? "SUCCESS" : "FAILED",
                               esc(text)));
  }
  if (const auto t = number("time_to_goal_s")) {
    row("time to the goal", fmt::format("{:.1f} s (sim), from the mission's start", *t));
  }
  if (const auto sim = number("sim_seconds"); sim && number("wall_seconds")) {
    row("run", fmt::format("{:.1f} s of sim time in {:.1f} s of wall time", *sim, *number("wall_seconds")));
  }
  if (const auto avg = number("average_speed_mps"); avg || number("top_speed_mps")) {
    row("speed", fmt::format("{} average, {} top", avg ? fmt::format("{:.1f} m/s", *avg) : std::string("-"),
                             number("top_speed_mps") ? fmt::format("{:.1f} m/s", *number("top_speed_mps")) : "-"));
  }
  if (const auto r = number("flown_over_optimum")) {
    row("flown / optimum", fmt::format("{:.3f} ({:.1f} m flown, {:.1f} m the known-map optimum)", *r,
                                       number("path_length_m").value_or(0.0), number("optimum_m").value_or(0.0)));
  } else if (const auto len = number("path_length_m")) {
    row("flown", fmt::format("{:.1f} m", *len));
  }
  if (const auto c = number("min_clearance_m")) {
    row("closest approach", fmt::format("{:.2f} m", *c));
  }
  if (const auto n = number("collisions")) {
    row("collisions", fmt::format("{}{:.0f}{}", *n > 0 ? "<b style=\"color:#c0392b\">" : "", *n, *n > 0 ? "</b>" : ""));
  }
  return rows_html.empty() ? std::string() : "<h2>Outcome</h2>\n<table>\n" + rows_html + "</table>\n";
}

/// A fault run's verdict as reactions to draw, checked: a malformed file names its key.
std::vector<Reaction> reactionsOf(const Json& verdict, const fs::path& file)
{
  const auto bad = [&](const std::string& what) { return ReportError(fmt::format("{}: {}", file.string(), what)); };
  if (!verdict.is_object() || !verdict.contains("rows") || !verdict["rows"].is_array()) {
    throw bad("no 'rows' list");
  }
  std::vector<Reaction> out;
  std::string step;
  for (std::size_t k = 0; k < verdict["rows"].size(); ++k) {
    const Json& r = verdict["rows"][k];
    for (const char* key : {"step", "expectation", "bound", "measured"}) {
      if (!r.contains(key) || !r[key].is_string()) {
        throw bad(fmt::format("rows[{}].{}: not a string", k, key));
      }
    }
    if (!r.contains("pass") || !r["pass"].is_boolean()) {
      throw bad(fmt::format("rows[{}].pass: not true or false", k));
    }
    step = r["step"].get<std::string>().empty() ? step : r["step"].get<std::string>();
    if (r.contains("within_s") && r["within_s"].is_number()) {
      Reaction reaction{fmt::format("{}: {}", step, r["expectation"].get<std::string>()), r["within_s"].get<double>(), std::nullopt};
      if (r.contains("measured_s") && r["measured_s"].is_number()) {
        reaction.measured_s = r["measured_s"].get<double>();
      }
      out.push_back(reaction);
    }
  }
  return out;
}

std::string verdictTable(const Json& verdict)
{
  std::string html = fmt::format("<h2>Faults and reactions</h2>\n<p>Scenario <code>{}</code>: {}.</p>\n<table>\n"
                                 "<tr><th>step</th><th>fault</th><th>expectation</th><th>bound</th><th>measured</th><th>result</th></tr>\n",
                                 esc(verdict.value("scenario", std::string())),
                                 verdict.value("passed", false) ? "every check passed" : "<b>checks failed</b>");
  for (const Json& r : verdict["rows"]) {
    const bool pass = r["pass"].get<bool>();
    html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td style=\"color:{}\">{}</td></tr>\n",
                        esc(r["step"].get<std::string>()), esc(r.value("fault", std::string())),
                        esc(r["expectation"].get<std::string>()), esc(r["bound"].get<std::string>()),
                        esc(r["measured"].get<std::string>()), pass ? "#27864a" : "#c0392b", pass ? "PASS" : "FAIL");
  }
  return html + "</table>\n";
}

struct Inputs {
  fs::path recording;
  fs::path output;
  std::optional<Json> summary;
  std::optional<Json> faults;  ///< quad fault's verdict (fault_report.json)
  fs::path faults_file;
  std::optional<fs::path> world;
  std::string name;  ///< the run's folder or the recording's name
};

Inputs resolve(const ReportOptions& options)
{
  Inputs in;
  std::error_code ec;
  if (fs::is_directory(options.input, ec)) {
    in.recording = options.recording.value_or(options.input / kRecordingFile);
    if (!fs::exists(in.recording)) {
      throw ReportError(fmt::format("{}: no recording (a run records unless --no-record; or name a recording)",
                                    in.recording.string()));
    }
    in.output = options.input;
    in.summary = readJson(options.input / "summary.json");
    in.faults_file = options.input / "fault_report.json";
    in.faults = readJson(in.faults_file);
    if (const auto run = readJson(options.input / "run.json"); run && run->contains("world") && (*run)["world"].is_string() &&
                                                             !(*run)["world"].get<std::string>().empty()) {
      in.world = (*run)["world"].get<std::string>();
    }
    in.name = fs::absolute(options.input).lexically_normal().filename().string();
    if (in.name.empty()) {
      in.name = fs::absolute(options.input).lexically_normal().parent_path().filename().string();
    }
  } else if (fs::exists(options.input, ec)) {
    in.recording = options.input;
    in.output = options.input.has_parent_path() ? options.input.parent_path() : fs::path(".");
    in.name = options.input.filename().string();
  } else {
    throw ReportError(fmt::format("{}: no such run folder or recording", options.input.string()));
  }
  if (options.output) {
    in.output = *options.output;
  }
  if (options.world) {
    in.world = *options.world;
  }
  return in;
}

std::string page(const Inputs& in, const FlightData& flight, const std::vector<Figure>& figures)
{
  std::string html = pageHead("quad report: " + in.name);
  html += fmt::format("<p>Recording <code>{}</code>: {} messages, sim time {:.2f} s to {:.2f} s.{}</p>\n",
                      esc(in.recording.filename().string()), flight.messages, flight.t_first_s, flight.t_last_s,
                      in.world ? " World <code>" + esc(in.world->filename().string()) + "</code>." : "");
  if (in.summary) {
    html += headline(*in.summary);
  }
  if (in.faults) {
    html += verdictTable(*in.faults);
  }
  html += "<h2>Figures</h2>\n";
  for (const Figure& f : figures) {
    html += figureElement(f.file, f.caption);
  }
  if (in.summary) {
    // every key, the processes' internals among them, below what a reader looks at first
    html += "<h2>Every figure of the summary</h2>\n<table>\n";
    rows(*in.summary, "", html);
    html += "</table>\n";
  }
  html += "</body>\n</html>\n";
  return html;
}

void writeFile(const fs::path& file, const std::string& text)
{
  std::ofstream out(file, std::ios::binary);
  out << text;
  out.close();
  if (!out) {
    throw ReportError(fmt::format("{}: cannot write", file.string()));
  }
}

}  // namespace

ReportResult writeReport(const ReportOptions& options, const std::function<void(const std::string&)>& say)
{
  const auto tell = [&](const std::string& line) {
    if (say) {
      say(line);
    }
  };
  const Inputs in = resolve(options);
  std::optional<world::World> world;
  if (in.world) {
    try {
      world = world::loadWorld(*in.world);
    } catch (const std::exception& e) {
      throw ReportError(fmt::format("{}: the world does not load: {}", in.world->string(), e.what()));
    }
  }
  std::error_code ec;
  const auto bytes = fs::file_size(in.recording, ec);
  tell(fmt::format("reading {} ({:.1f} MB)", in.recording.string(), ec ? 0.0 : static_cast<double>(bytes) / 1e6));
  bag::McapContents contents;
  try {
    // Tolerant: a recording a killed recorder left is reported up to its last whole chunk.
    contents = bag::readMcap(in.recording, true);
  } catch (const bag::BagError& e) {
    throw ReportError(e.what());
  }
  if (!contents.problem.empty()) {
    tell(fmt::format("{}: {}: reporting what came before", in.recording.string(), contents.problem));
  }
  FlightData flight;
  try {
    flight = readFlight(
        contents,
        [&](std::size_t done, std::size_t total) {
          tell(fmt::format("decoded {} of {} messages ({:.0f}%)", done, total,
                           total == 0 ? 100.0 : 100.0 * static_cast<double>(done) / static_cast<double>(total)));
        },
        options.vehicle);
  } catch (const FlightError& e) {
    throw ReportError(fmt::format("{}: {}", in.recording.string(), e.what()));
  }
  std::vector<Figure> figures = flightFigures(flight, world ? &*world : nullptr);
  if (in.faults) {
    const std::vector<Reaction> reactions = reactionsOf(*in.faults, in.faults_file);
    if (!reactions.empty()) {
      figures.push_back(reactionsFigure(in.faults->value("scenario", std::string()), reactions));
    }
  }
  fs::create_directories(in.output, ec);
  int k = 0;
  for (const Figure& f : figures) {
    writeFile(in.output / f.file, f.svg);
    tell(fmt::format("figure {} of {}: {}", ++k, figures.size(), (in.output / f.file).string()));
  }
  const fs::path html = in.output / "report.html";
  writeFile(html, page(in, flight, figures));
  return {html, static_cast<int>(figures.size())};
}

}  // namespace quad::report
