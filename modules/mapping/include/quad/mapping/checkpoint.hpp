// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The mapper's state on disk, so that a mapper started again mid-run resumes where it was:
/// the octree with its log-odds (not OctoMap's maximum-likelihood .bt, which would forget
/// how sure each voxel is), the first update number it may use, and the sim time of the
/// newest scan in it. Written whole or not at all (a temporary file renamed over the old).
///
/// Update numbers must grow across a restart: the planner's MapFollower drops a number it
/// has seen. The checkpoint therefore reserves numbers ahead (`next_update_seq`), and the
/// mapper writes a new checkpoint before it would publish past the reservation.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "quad/mapping/mapper.hpp"

namespace quad::mapping {

struct MapCheckpoint {
  std::uint64_t next_update_seq = 1;  ///< no update before the checkpoint was numbered this or higher
  std::int64_t stamp_ns = 0;          ///< [ns] sim time of the newest scan integrated
};

/// Writes `mapper`'s tree and `meta` to `file` (via `file`.tmp, renamed). Throws
/// std::runtime_error naming the file when it cannot.
void writeCheckpoint(const std::filesystem::path& file, const Mapper& mapper, const MapCheckpoint& meta);
/// The same, for a tree of `resolution` whose node data (treeDataBytes) the caller has.
void writeCheckpoint(const std::filesystem::path& file, double resolution, const std::vector<std::uint8_t>& tree_data,
                     const MapCheckpoint& meta);

/// Reads `file` into `mapper`, which must hold nothing yet. Nothing when the file does not
/// exist. Throws std::runtime_error naming the file when it is not a checkpoint, is cut
/// short, or has another resolution than the mapper.
std::optional<MapCheckpoint> readCheckpoint(const std::filesystem::path& file, Mapper& mapper);

}  // namespace quad::mapping
