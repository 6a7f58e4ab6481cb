// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A campaign's sweep: the axes it varies beyond worlds and seeds (a module's parameter, a
/// parameter of a world's generators) and the product of all of them, a run per cell.

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace quad::campaign {

/// One axis: `MODULE:KEY` (a parameter of one module of the manifest, as `quad launch --set`
/// gives it) or `world:TYPE.KEY` (that key of every generator of that type in the world,
/// e.g. world:forest.density), and the values it takes, as YAML scalars.
struct Axis {
  std::string key;
  std::vector<std::string> values;

  bool isWorld() const { return key.starts_with("world:"); }
  /// The generator type and its key of a world axis ("forest", "density").
  std::pair<std::string, std::string> generatorKey() const;
  /// The last word of its key ("max_speed", "density"): its column and folder name.
  std::string shortName() const;
};

/// Each axis's label, in its runs' folder names and its table column: its short name, or,
/// where two axes share one or it is "seed" (the plant's seed has it), its key without
/// "world:" ("forest.seed", "control_x.seed").
std::vector<std::string> axisLabels(const std::vector<Axis>& axes);

/// "control:follower.max_speed=3,5,7,10" or "world:forest.seed=1..10" (whole numbers from one
/// to the other) read as an Axis. Throws common::ConfigError naming `origin` and the text.
Axis parseAxis(const std::string& text, const std::string& origin);

/// An axis's values from a list or a scalar ("1..10" a range, else one value); `origin` names
/// it in errors.
std::vector<std::string> axisValues(const std::string& text, const std::string& origin);

/// One cell of the product: a world, one value of each axis, a seed.
struct PlannedRun {
  std::filesystem::path world;  ///< the world file as given
  std::vector<std::pair<std::string, std::string>> params;  ///< axis key and value, in axis order
  std::uint64_t seed = 1;
  /// Its folder's name, unique in the campaign: "benchmark_forest-density0.04-max_speed7-seed1";
  /// past 160 characters, cut and ended with a digest of the whole.
  std::string name;

  /// Its params of module axes as `quad launch --set` texts.
  std::vector<std::string> moduleSets() const;
  /// Its params of world axes.
  std::vector<std::pair<std::string, std::string>> worldParams() const;
};

/// Every world x each axis's values x seeds 1..seeds, the worlds outermost and the seeds
/// innermost, each once. Throws common::ConfigError for an axis without values or an axis
/// named twice.
std::vector<PlannedRun> planRuns(const std::vector<std::filesystem::path>& worlds, const std::vector<Axis>& axes,
                                 int seeds);

/// The world file's text with the world axes' values set in its generators of their types,
/// and its maps' files made absolute (the text is read from another folder). Throws
/// common::ConfigError naming the file and axis when it has no generator of that type.
std::string worldVariant(const std::filesystem::path& world,
                         const std::vector<std::pair<std::string, std::string>>& world_params);

}  // namespace quad::campaign
