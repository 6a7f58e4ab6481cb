// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad report RUN_DIR|RECORDING`: report.html and a figure per SVG file (tools/report/).

#include "quad/report/report.hpp"

namespace quad::tools {

/// 0 when written; 1 when the input cannot be reported (the reason, naming the file, on
/// stderr). Progress goes to stderr unless `quiet`.
int report(const report::ReportOptions& options, bool quiet);

}  // namespace quad::tools
