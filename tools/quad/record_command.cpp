// SPDX-License-Identifier: BSD-3-Clause
#include "bag_commands.hpp"

#include <atomic>

#include "quad/runtime/node.hpp"

namespace quad::tools {

namespace {
std::atomic<int> g_stop{0};
}  // namespace

int record(const record::RecordOptions& options)
{
  runtime::SignalWatcher signals;  // before any thread exists
  signals.onSignal([](int s) { g_stop.store(s); });
  return record::record(options, g_stop);
}

}  // namespace quad::tools
