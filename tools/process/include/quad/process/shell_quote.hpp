// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A word for a POSIX shell: what the launcher sends over ssh and what a cluster's task script
/// runs.

#include <string>

namespace quad::process {

/// `word` as one word for a POSIX shell, whatever it contains: in single quotes, each single
/// quote in it written '\''.
std::string shellQuote(const std::string& word);

}  // namespace quad::process
