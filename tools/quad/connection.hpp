#pragma once
/// @file
/// Helpers the quad subcommands share: their participant, and topic lookup with a clear error.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "quad/dds/participant.hpp"
#include "quad/dds/raw_type.hpp"
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

/// The fields of a sample of `info`'s type read from YAML `values` (as `quad topic pub`
/// takes them); throws std::invalid_argument naming the topic, the field and the value when
/// they do not make a sample.
nlohmann::ordered_json sampleValues(const dds::TopicInfo& info, const std::string& values);

/// `sample` as CDR, its Header filled where the values leave it unset. `enforce_bounds`
/// false writes strings and sequences past their IDL bounds as given (fault injection).
dds::RawSample encodeSample(const dds::TopicInfo& info, nlohmann::ordered_json sample, std::int64_t stamp_ns,
                            std::uint64_t seq, std::uint32_t vehicle_id, bool enforce_bounds = true);

}  // namespace quad::tools
