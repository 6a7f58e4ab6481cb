// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The recorder as a module a container hosts (`quad_container --module record --set
/// output=FILE`): a node on the container's participant whose readers take the samples of
/// the modules beside it on their writers' threads, with no socket between; the launcher
/// hosts it so in the composed layout (docs/recording.md).

#include "quad/runtime/module_main.hpp"

namespace quad::record {

/// Its parameters: `output` (the MCAP file, required), `topics` and `exclude` (globs, as
/// quad record's). It is built after the modules it records and stopped after them.
runtime::ModuleEntry recorderModule();

}  // namespace quad::record
