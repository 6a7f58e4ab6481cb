// SPDX-License-Identifier: BSD-3-Clause
#include "quad/report/page.hpp"

#include <fmt/format.h>

#include "quad/common/xml_text.hpp"

namespace quad::report {

std::string pageHead(const std::string& title, const std::string& extra_style)
{
  return fmt::format(R"(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>{0}</title>
<link rel="icon" href="data:,">
<style>
body {{ font-family: sans-serif; margin: 2em auto; max-width: 960px; color: #222; }}
table {{ border-collapse: collapse; margin: 1em 0; }}
th, td {{ text-align: left; padding: 2px 12px 2px 0; border-bottom: 1px solid #eee; font-size: 14px; }}
th {{ font-weight: normal; color: #555; }}
figure {{ margin: 2em 0; }}
figure img {{ max-width: 100%; border: 1px solid #ddd; }}
figcaption {{ font-size: 14px; color: #444; }}
{1}</style>
</head>
<body>
<h1>{0}</h1>
)",
                     common::xmlEscaped(title), extra_style);
}

std::string figureElement(const std::string& file, const std::string& caption)
{
  return fmt::format("<figure><img src=\"{0}\" alt=\"{1}\"><figcaption>{1}</figcaption></figure>\n",
                     common::xmlEscaped(file), common::xmlEscaped(caption));
}

}  // namespace quad::report
