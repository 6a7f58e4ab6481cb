#pragma once
/// @file
/// Helpers the quad subcommands share: their participant, and topic lookup with a clear error.

#include <string>
#include <string_view>
#include <vector>

#include "quad/dds/participant.hpp"
#include "quad/dds/topic.hpp"
#include "topic_commands.hpp"

namespace quad::tools {

/// Participant options from the environment, with the command line's overrides.
dds::ParticipantOptions participantOptions(const std::string& name,
                                           const ConnectionOptions& connection);

/// Whether `topic` matches one of the shell globs (`quad/sim/*`).
bool matchesAnyGlob(const std::string& topic, const std::vector<std::string>& globs);

/// The contract of `name`; throws std::invalid_argument listing near names when there is none.
dds::TopicInfo requireTopic(std::string_view name);

}  // namespace quad::tools
