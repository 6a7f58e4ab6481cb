// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The composed layout: a manifest's `containers` each made one process (quad_container)
// hosting its modules.

#include <filesystem>
#include <string>
#include <vector>

#include "quad/launch/manifest.hpp"

namespace quad::launch {

/// The process that hosts `members` (the container's modules, in start order): quad_container
/// at `program` (each member's config and sets after its --module: processCommand), on the
/// members' one host,
/// with their environments, waiting for what they need that none of them writes
/// (`topic_owner`), ending the run if one does, restarted as often as the most any allows,
/// given as long to be ready as the longest. What cannot be composed (members on two hosts,
/// an environment variable with two values, members of two vehicles, a member with args)
/// goes to `problems`. A fleet's container takes its vehicle's id.
Module composeContainer(const ContainerSpec& spec, const std::vector<const Module*>& members,
                        const std::filesystem::path& program, const ProgramLookup& lookup,
                        std::vector<std::string>& problems);

/// With DDS Security a container is one participant, so one identity: named as its participant
/// is (common::containerName of its modules, in start order), made by `quad security init DIR
/// --container ...`. Its certificate missing from `security_dir` goes to `problems`, with the
/// command that makes it.
void checkContainerIdentity(const Module& container, const std::filesystem::path& security_dir,
                            std::vector<std::string>& problems);

}  // namespace quad::launch
