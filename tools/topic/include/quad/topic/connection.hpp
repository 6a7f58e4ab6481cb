// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// What the quad subcommands share to reach a running stack: their participant's options,
/// and topic lookup with a clear error.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "quad/dds/participant.hpp"
#include "quad/dds/topic.hpp"

namespace quad::topic {

/// What every quad command shares: the domain and discovery of the running stack. Unset
/// fields come from the environment (QUAD_DOMAIN_ID, ...), as for every module.
struct ConnectionOptions {
  std::optional<int> domain_id;
  /// `--vehicle`: the vehicle a command reads (only its samples) and writes for (its header's
  /// vehicle_id); unset: QUAD_VEHICLE_ID for writing, every vehicle's samples for reading.
  std::optional<std::uint32_t> vehicle_id;
};

/// Whether a sample read under `connection` is one to show: any with no `--vehicle`, else one
/// whose header names that vehicle.
bool selectedVehicle(const ConnectionOptions& connection, std::span<const std::uint8_t> payload);

/// Participant options from the environment, with the command line's overrides.
dds::ParticipantOptions participantOptions(const std::string& name,
                                           const ConnectionOptions& connection);

/// Whether `topic` matches one of the shell globs (`quad/sim/*`).
bool matchesAnyGlob(const std::string& topic, const std::vector<std::string>& globs);

/// The contract of `name`; throws std::invalid_argument listing near names when there is none.
dds::TopicInfo requireTopic(std::string_view name);

}  // namespace quad::topic
