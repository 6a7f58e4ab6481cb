// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// How a process hosts quad's modules: one module alone (each module's own program), or
/// several on one shared participant (a container, `quad_container`), each still a node with
/// its own readers, writers and thread, on the same topics.

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "quad/common/params.hpp"
#include "quad/dds/participant.hpp"
#include "quad/runtime/node.hpp"

namespace quad::runtime {

/// What a process needs to host a module: its name, the schema of its parameters, and how to
/// build its node of checked params on a participant handle.
struct ModuleEntry {
  std::string name;
  common::ParamSchema schema;
  std::function<std::unique_ptr<Node>(const common::Params&, dds::Participant)> make;
  /// A recorder of the others (the run's recording, hosted): a container builds it after
  /// its modules, so that it reads their topics with the types they registered, stops it
  /// after them, so that it has their last samples, and leaves it out of its name (and so of
  /// its participant's and its DDS Security identity's).
  bool records = false;
};

/// The entry of the usual module: a `NodeType(Config, Participant)` built of the config that
/// `config_from` makes of the params (`Config config_from(const common::Params&)`).
template <typename NodeType, typename ConfigFrom>
ModuleEntry moduleEntry(std::string name, common::ParamSchema schema, ConfigFrom config_from)
{
  return {std::move(name), std::move(schema), [config_from](const common::Params& params, dds::Participant participant) {
            return std::make_unique<NodeType>(config_from(params), std::move(participant));
          }};
}

/// The body of every node's main(): installs signal handling, builds the node with `make`,
/// runs it, and turns an exception into one logged line and exit status 1. Once the node
/// stopped, it ends the process itself, without destroying the node: its participant is
/// removed first, and what it must leave behind it wrote when it stopped (Node::onStop).
int runNode(std::string_view module_name, const std::function<std::unique_ptr<Node>()>& make);

/// runNode() for a node with parameters: reads `--config FILE` and `--set KEY=VALUE` from the
/// command line (the schema's defaults without them), validates them against `schema` (plus
/// the logging keys, which set up logging), and hands the params to `make`. A bad command
/// line or config is refused before any DDS entity exists: each problem is logged as
/// `file:key: value: reason` and the exit status is 1 (2 for a bad argument).
int runNodeMain(int argc, char** argv, std::string_view module_name, common::ParamSchema schema,
                const std::function<std::unique_ptr<Node>(const common::Params&)>& make);

/// A module's main: runNodeMain for `module` on a participant of its own, with the options
/// of the environment.
int runModule(int argc, char** argv, const ModuleEntry& module);

/// The container's main: hosts the modules the command line names, each of `known`,
/// on one participant of the environment's options (named common::containerName() of the
/// modules that do not record):
///   --module NAME [--config FILE] [--set KEY=VALUE]... [--module NAME ...]
/// Every module's config is checked before any DDS entity exists (as runNodeMain's). Each
/// node runs on a thread of its own; the container lives and dies as one process: a node that
/// stops on its own (its run ended, or it failed) stops the others, a signal stops them all,
/// and the exit status is 1 when any failed. The process ends as runNode's does.
int runContainer(int argc, char** argv, const std::vector<ModuleEntry>& known);

}  // namespace quad::runtime
