// SPDX-License-Identifier: BSD-3-Clause
#include "bridge_command.hpp"

#include <atomic>

#include "quad/runtime/node.hpp"

namespace quad::tools {

namespace {
std::atomic<int> g_stop{0};
}  // namespace

int bridge(const bridge::BridgeOptions& options)
{
  runtime::SignalWatcher signals;  // before any thread exists
  signals.onSignal([](int s) { g_stop.store(s); });
  return bridge::runBridge(options, g_stop);
}

}  // namespace quad::tools
