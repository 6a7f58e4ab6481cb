// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad report`: a run's recording turned into report.html and one SVG file per figure, in
/// the run's folder. The page needs no network and no script: any browser opens it.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

namespace quad::report {

/// What cannot be reported (no recording, an unreadable file, a world that does not load):
/// names the file and the problem.
class ReportError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct ReportOptions {
  /// A run's folder (its recording.mcap, summary.json and run.json), or a recording.
  std::filesystem::path input;
  /// Where report.html and the figures go; default: the run's folder, or the recording's.
  std::optional<std::filesystem::path> output;
  /// The world file whose obstacles the views draw; default: the run's (run.json).
  std::optional<std::filesystem::path> world;
  /// A run folder's recording when it is not the folder's recording.mcap (quad launch
  /// --record FILE).
  std::optional<std::filesystem::path> recording;
  /// A fleet's run: the vehicle reported (Header.vehicle_id); a recording of one vehicle needs none.
  std::optional<std::uint32_t> vehicle;
};

struct ReportResult {
  std::filesystem::path html;  ///< report.html
  int figures = 0;
};

/// Where a run folder keeps its recording.
inline constexpr const char* kRecordingFile = "recording.mcap";

/// Writes the report; `say` gets a line of progress now and then. Throws ReportError.
ReportResult writeReport(const ReportOptions& options, const std::function<void(const std::string&)>& say = {});

}  // namespace quad::report
