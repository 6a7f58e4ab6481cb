// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A fuzz harness: LLVMFuzzerTestOneInput, as libFuzzer calls it, built either with clang's
/// libFuzzer (the long runs) or with driver.cpp (the CI-sized runs under any compiler).
/// Whatever the bytes, a harness returns; a crash, a sanitizer report or an abort is a
/// finding.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace quad::fuzz {

/// Inputs to start from besides the corpus folders given on the command line; a harness may
/// define it (driver.cpp only).
std::vector<std::string> seeds();

}  // namespace quad::fuzz
