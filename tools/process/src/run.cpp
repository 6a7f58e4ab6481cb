// SPDX-License-Identifier: BSD-3-Clause
#include "quad/process/run.hpp"

#include <poll.h>

#include <optional>
#include <stdexcept>

#include "quad/process/spawn.hpp"

namespace quad::process {

RunResult run(const std::vector<std::string>& argv)
{
  Spawned child(argv);
  RunResult result;
  std::optional<int> status;
  while (!(status = child.poll())) {
    pollfd p{child.outputFd(), POLLIN, 0};
    ::poll(&p, 1, 20);
    child.readOutput(result.output);
  }
  child.readOutput(result.output);
  result.status = *status;
  return result;
}

void runChecked(const std::vector<std::string>& argv)
{
  auto result = run(argv);
  if (result.status != 0) {
    std::string line;
    for (const auto& a : argv) {
      line += (line.empty() ? "" : " ") + a;
    }
    while (!result.output.empty() && result.output.back() == '\n') {
      result.output.pop_back();
    }
    throw std::runtime_error("'" + line + "' failed (" + describeStatus(result.status) + "): " + result.output);
  }
}

}  // namespace quad::process
