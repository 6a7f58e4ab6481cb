// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad bridge`: a live Foxglove WebSocket server for the running stack (tools/bridge).

#include "quad/bridge/bridge.hpp"

namespace quad::tools {

/// Serves until Ctrl-C or SIGTERM; returns the exit status.
int bridge(const bridge::BridgeOptions& options);

}  // namespace quad::tools
