// SPDX-License-Identifier: BSD-3-Clause
#include "report_command.hpp"

#include <cstdio>

namespace quad::tools {

int report(const report::ReportOptions& options, bool quiet)
{
  try {
    const auto result = report::writeReport(options, [quiet](const std::string& line) {
      if (!quiet) {
        std::fprintf(stderr, "report: %s\n", line.c_str());
      }
    });
    std::printf("%s (%d figures)\n", result.html.string().c_str(), result.figures);
    return 0;
  } catch (const report::ReportError& e) {
    std::fprintf(stderr, "report: %s\n", e.what());
    return 1;
  }
}

}  // namespace quad::tools
