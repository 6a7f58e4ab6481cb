// SPDX-License-Identifier: BSD-3-Clause
#include "fault_command.hpp"

#include "quad/launch/run.hpp"
#include "quad/runtime/node.hpp"

namespace quad::tools {

int fault(const fault::FaultOptions& options)
{
  runtime::SignalWatcher signals;  // before any thread exists
  signals.onSignal([](int s) { launch::LaunchRun::received_signal.store(s); });
  return fault::runScenario(options);
}

}  // namespace quad::tools
