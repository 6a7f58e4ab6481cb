// SPDX-License-Identifier: BSD-3-Clause
// The standalone fuzz driver, for builds without libFuzzer: runs every seed and corpus file,
// then mutations of them (bit flips, interesting values, inserted, removed and repeated
// ranges, splices), from a seeded generator, for a number of runs or seconds.
//
//   fuzz_rtps_check [--runs N] [--seconds S] [--seed K] [CORPUS_FILE_OR_FOLDER...]
//
// A crash ends the process with the signal, as a libFuzzer crash does; the input that
// caused it is written to crash-<seed>-<run>.bin first when the harness aborts.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "harness.hpp"

namespace {

namespace fs = std::filesystem;
using Input = std::string;

std::vector<Input> readCorpus(const fs::path& path)
{
  std::vector<Input> inputs;
  const auto read = [&](const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    inputs.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  if (fs::is_directory(path)) {
    for (const auto& e : fs::recursive_directory_iterator(path)) {
      if (e.is_regular_file()) {
        read(e.path());
      }
    }
  } else if (fs::is_regular_file(path)) {
    read(path);
  } else {
    std::fprintf(stderr, "fuzz: %s: no such file or folder\n", path.c_str());
    std::exit(2);
  }
  return inputs;
}

/// One random change, of the kinds that break lengths, counts and offsets.
void mutate(Input& in, std::mt19937_64& rng, const std::vector<Input>& pool)
{
  const auto pick = [&](std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng() % n); };
  static const std::uint32_t kInteresting[] = {0, 1, 2, 3, 4, 7, 8, 15, 16, 31, 32, 63, 64, 127, 128, 255, 256,
                                               1024, 4096, 32767, 32768, 65535, 65536, 0x7fffffff, 0x80000000,
                                               0xfffffffe, 0xffffffff};
  switch (rng() % 8) {
    case 0:  // flip a bit
      if (!in.empty()) {
        in[pick(in.size())] ^= static_cast<char>(1u << (rng() % 8));
      }
      break;
    case 1:  // a random byte
      if (!in.empty()) {
        in[pick(in.size())] = static_cast<char>(rng());
      }
      break;
    case 2:
    case 3: {  // an interesting 1, 2 or 4-byte value, either order
      if (in.empty()) {
        break;
      }
      const std::uint32_t v = kInteresting[pick(std::size(kInteresting))];
      const std::size_t width = std::size_t{1} << (rng() % 3);
      const std::size_t at = pick(in.size());
      const bool big = rng() % 2 == 0;
      for (std::size_t i = 0; i < width && at + i < in.size(); ++i) {
        const std::size_t shift = 8 * (big ? width - 1 - i : i);
        in[at + i] = static_cast<char>(v >> shift);
      }
      break;
    }
    case 4:  // remove a range
      if (!in.empty()) {
        const std::size_t at = pick(in.size());
        in.erase(at, 1 + pick(std::min<std::size_t>(in.size() - at, 64)));
      }
      break;
    case 5: {  // insert random bytes
      const std::size_t at = pick(in.size() + 1);
      Input bytes(1 + pick(32), '\0');
      for (auto& c : bytes) {
        c = static_cast<char>(rng());
      }
      in.insert(at, bytes);
      break;
    }
    case 6:  // repeat a range
      if (!in.empty()) {
        const std::size_t at = pick(in.size());
        const std::size_t n = 1 + pick(std::min<std::size_t>(in.size() - at, 128));
        in.insert(pick(in.size() + 1), in.substr(at, n));
      }
      break;
    default: {  // splice another input's tail
      const Input& other = pool[pick(pool.size())];
      if (!other.empty()) {
        in = in.substr(0, pick(in.size() + 1)) + other.substr(pick(other.size()));
      }
      break;
    }
  }
  if (in.size() > 1 << 20) {
    in.resize(1 << 20);
  }
}

const Input* current = nullptr;
std::uint64_t current_seed = 0;
std::uint64_t current_run = 0;

void saveCurrent(int signal)
{
  if (current != nullptr) {
    char name[64];
    std::snprintf(name, sizeof(name), "crash-%llu-%llu.bin", static_cast<unsigned long long>(current_seed),
                  static_cast<unsigned long long>(current_run));
    if (std::FILE* f = std::fopen(name, "wb")) {
      std::fwrite(current->data(), 1, current->size(), f);
      std::fclose(f);
    }
    std::fprintf(stderr, "fuzz: signal %d on run %llu; input written to %s\n", signal,
                 static_cast<unsigned long long>(current_run), name);
  }
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

int run(const Input& in)
{
  current = &in;
  return LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(in.data()), in.size());
}

}  // namespace

int main(int argc, char** argv)
{
  std::uint64_t runs = 100'000;
  double seconds = 0.0;
  std::uint64_t seed = 1;
  std::vector<Input> pool = quad::fuzz::seeds();
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--runs" || a == "--seconds" || a == "--seed") && i + 1 < argc) {
      const char* v = argv[++i];
      if (a == "--runs") {
        runs = std::strtoull(v, nullptr, 10);
      } else if (a == "--seconds") {
        seconds = std::strtod(v, nullptr);
      } else {
        seed = std::strtoull(v, nullptr, 10);
      }
    } else {
      auto more = readCorpus(a);
      pool.insert(pool.end(), more.begin(), more.end());
    }
  }
  for (int s : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) {
    std::signal(s, saveCurrent);
  }
  current_seed = seed;
  if (pool.empty()) {
    pool.emplace_back();
  }
  for (const auto& in : pool) {
    run(in);
  }
  std::mt19937_64 rng(seed);
  const auto start = std::chrono::steady_clock::now();
  std::uint64_t done = 0;
  for (; seconds > 0.0 || done < runs; ++done) {
    if (seconds > 0.0 && (done & 255) == 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= seconds) {
      break;
    }
    current_run = done;
    Input in = pool[static_cast<std::size_t>(rng() % pool.size())];
    const int changes = 1 + static_cast<int>(rng() % 6);
    for (int c = 0; c < changes; ++c) {
      mutate(in, rng, pool);
    }
    run(in);
  }
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("fuzz: %zu seed inputs and %llu mutations in %.1f s (%.0f/s), seed %llu: no crash\n", pool.size(),
              static_cast<unsigned long long>(done), took, static_cast<double>(done) / std::max(took, 1e-9),
              static_cast<unsigned long long>(seed));
  return 0;
}
