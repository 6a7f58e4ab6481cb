// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A lockstep run's recorder holds the run's start (QUAD_LOCKSTEP_RECORDER, docs/recording.md):
/// the plant counts it among its lockstep participants, and it reports itself done for good,
/// for each vehicle, once it holds that vehicle's clock and reads every topic the plant writes.

#include <cstdint>
#include <set>

#include "quad/dds/raw_type.hpp"

namespace quad::record {

class StartGate {
public:
  /// Writes its reports with raw payloads, as every endpoint of the recorder's participant.
  explicit StartGate(dds::Participant& participant);

  /// A clock sample of `vehicle`, at sim time `sim_ns`, was recorded.
  void clockSeen(std::uint32_t vehicle, std::int64_t sim_ns);

  /// A vehicle's clock came and it was not released yet.
  bool waiting() const { return !waiting_.empty(); }

  /// Once `plant_matched` (every recorded plant topic has its writer matched): reports done for
  /// good for each vehicle whose clock came and that was not released yet.
  void release(bool plant_matched);

private:
  dds::RawPublisher reports_;
  std::set<std::uint32_t> waiting_;   // vehicles whose clock came, not reported yet
  std::set<std::uint32_t> released_;
  std::int64_t clock_ns_ = 0;         // the newest clock's sim time: the reports' stamp
  std::uint64_t seq_ = 0;
};

}  // namespace quad::record
