// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The HTML pages quad writes beside their SVG figures (a run's report.html, a campaign's
/// campaign.html): one file each, no script, opened offline by any browser, in one style.

#include <string>

namespace quad::report {

/// The page up to and including its <h1>: the document's head with the shared style (and
/// `extra_style`, CSS rules of the page's own), the title as <title> and <h1>.
std::string pageHead(const std::string& title, const std::string& extra_style = "");

/// A figure: its SVG file (beside the page) and its caption, both escaped.
std::string figureElement(const std::string& file, const std::string& caption);

}  // namespace quad::report
