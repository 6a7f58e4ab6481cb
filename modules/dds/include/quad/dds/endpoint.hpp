// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The untyped halves of Publisher<T> and Subscriber<T>: entity ownership and status listeners.

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "quad/dds/participant.hpp"
#include "quad/dds/topic.hpp"
#include "quad/dds/waker.hpp"

namespace quad::dds {

/// After a writer matched its first reader, how long before writing what a volatile reader
/// must not miss: the reader's side of discovery completes on its own schedule, and until then
/// it drops the writer's samples.
inline constexpr std::chrono::milliseconds kReaderMatchSettle{300};

/// A participant's GUID prefix: which process (participant) an endpoint belongs to.
using ParticipantPrefix = std::array<std::uint8_t, 12>;

/// The endpoints an endpoint is matched with, by GUID, kept from its match callbacks (Fast DDS
/// 2.9 does not list them: get_matched_subscriptions is unsupported).
class MatchedPeers {
public:
  /// A peer matched (`change` > 0) or went away (< 0); `guid` is its 16-byte GUID.
  void update(const std::uint8_t* guid, int change);
  /// The participants of the peers matched now.
  std::vector<ParticipantPrefix> participants() const;

private:
  mutable std::mutex mutex_;
  std::vector<std::array<std::uint8_t, 16>> guids_;
};

/// Owns one DataWriter; reports matches, offered deadlines, liveliness and incompatible QoS
/// to the participant's event queue.
class WriterEndpoint {
public:
  /// `qos` replaces the contract's QoS profile (for tools and tests); normally left out.
  /// `partition`: the vehicle whose partitions the writer is in (vehiclePartitions); by default
  /// the participant's.
  WriterEndpoint(Participant& participant, const TopicInfo& info,
                 const eprosima::fastdds::dds::TypeSupport& type,
                 std::optional<eprosima::fastdds::dds::DataWriterQos> qos,
                 std::optional<std::uint32_t> partition = std::nullopt);
  ~WriterEndpoint();
  WriterEndpoint(const WriterEndpoint&) = delete;
  WriterEndpoint& operator=(const WriterEndpoint&) = delete;

  /// Number of readers matched now.
  int matchedReaders() const { return matched_.load(); }
  /// The participants of the readers matched now.
  std::vector<ParticipantPrefix> matchedReaderParticipants() const { return peers_.participants(); }
  std::uint64_t written() const { return written_.load(); }
  std::uint64_t failed() const { return failed_.load(); }
  const TopicInfo& info() const { return info_; }

  /// Asserts the writer's liveliness (for MANUAL_BY_TOPIC writers; a no-op for others).
  void assertLiveliness();
  /// The liveliness lease the writer offers (its QoS profile's) [ns]; none when infinite.
  std::optional<std::int64_t> livelinessLeaseNs() const;

  /// Waits until every matched reliable reader acknowledged what was written; false on timeout.
  bool waitForAcknowledgments(std::chrono::milliseconds timeout);

protected:
  /// Writes an already filled sample; a failure is counted and reported, never thrown.
  bool writeSample(void* sample);

private:
  class Listener;
  Participant& participant_;
  TopicInfo info_;
  std::unique_ptr<Listener> listener_;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
  std::atomic<int> matched_{0};
  MatchedPeers peers_;
  std::atomic<std::uint64_t> written_{0};
  std::atomic<std::uint64_t> failed_{0};
};

/// Owns one DataReader; wakes the node on data and reports statuses as events.
class ReaderEndpoint {
public:
  /// `partition` as the writer's: vehicle 0's hears every vehicle's writers.
  ReaderEndpoint(Participant& participant, const TopicInfo& info,
                 const eprosima::fastdds::dds::TypeSupport& type, Waker* waker,
                 std::optional<eprosima::fastdds::dds::DataReaderQos> qos,
                 std::optional<std::uint32_t> partition = std::nullopt);
  ~ReaderEndpoint();
  ReaderEndpoint(const ReaderEndpoint&) = delete;
  ReaderEndpoint& operator=(const ReaderEndpoint&) = delete;

  int matchedWriters() const { return matched_.load(); }
  /// The participants of the writers matched now.
  std::vector<ParticipantPrefix> matchedWriterParticipants() const { return peers_.participants(); }
  std::uint64_t deadlinesMissed() const { return deadlines_missed_.load(); }
  const TopicInfo& info() const { return info_; }
  /// The liveliness lease the reader asks of writers (its QoS profile's) [ns]; none when
  /// infinite.
  std::optional<std::int64_t> livelinessLeaseNs() const;

  /// A matched writer became alive, lost its liveliness (its process died, stopped or was
  /// cut off for longer than the contract's lease), or went away.
  struct WriterLiveliness {
    std::uint64_t writer = 0;  ///< the id takeSample gives for its samples
    bool alive = false;
    std::int64_t steady_ns = 0;  ///< when this reader learned it
  };
  /// The changes since the last call, oldest first.
  std::vector<WriterLiveliness> takeLivelinessChanges();

  /// Samples dropped because they were for another vehicle.
  std::uint64_t foreignSamples() const { return foreign_.load(); }

protected:
  /// Takes the next sample with valid data into `sample`; false when none is left. `writer`,
  /// when given, receives an id of the writer that sent it (a hash of its GUID);
  /// `received_ns`, the wall time (CLOCK_REALTIME) at which the middleware received it.
  /// Nothing is taken before Fast DDS first told the reader of data (docs/dds.md,
  /// "Publishers and subscribers"): 2.9.1 can let a sample be taken before it has counted
  /// the sample's instance, and then aborts on the instance's next sample.
  bool takeSample(void* sample, std::uint64_t* writer = nullptr, std::int64_t* received_ns = nullptr);
  /// True for a sample of this participant's vehicle; else counts it and reports it (the 1st,
  /// 2nd, 4th, 8th... time) as an event.
  bool ownVehicle(std::uint32_t vehicle_id);
  /// The same for a participant that serves several vehicles (a plant simulating a fleet):
  /// true when `vehicle_id` is one of `served`.
  bool servedVehicle(std::uint32_t vehicle_id, std::span<const std::uint32_t> served);

private:
  class Listener;
  Participant& participant_;
  TopicInfo info_;
  std::unique_ptr<Listener> listener_;
  eprosima::fastdds::dds::TopicDescription* topic_ = nullptr;  // the topic, or a filtered one of its own
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
  std::atomic<int> matched_{0};
  MatchedPeers peers_;
  std::atomic<std::uint64_t> deadlines_missed_{0};
  std::mutex liveliness_mutex_;
  std::vector<WriterLiveliness> liveliness_changes_;
  std::atomic<std::uint64_t> foreign_{0};
};

}  // namespace quad::dds
