// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A reader that wants at most one sample a period of sim time (a viewer drawing the vehicle
/// at 50 Hz from a 250 Hz state) says so with the DDS TIME_BASED_FILTER's minimum separation
/// (withMinimumSeparation). Fast DDS 2.9 accepts that policy and ignores it; quad honours it in
/// sim time, the samples' Header stamps, with a content filter of its own class that every
/// quad participant registers. A writer whose participant knows the class (every quad writer
/// with an infinite liveliness lease: the data topics' writers) evaluates it for that reader
/// and sends the reader only what passes, so the samples left out never cross the transport;
/// a sample from another writer is filtered where it is received.

#include <cstdint>
#include <map>
#include <mutex>

#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/IContentFilterFactory.hpp>

namespace quad::dds {

/// The filter class's name, as discovery carries it to the writers.
inline constexpr const char* kSimPeriodFilterClass = "QUAD_SIM_PERIOD";
/// Its one expression; parameter %0 is the period [ns of sim time], a positive integer.
inline constexpr const char* kSimPeriodFilterExpression = "first Header.stamp_ns in each %0 ns";

/// [ns] The start of the window after the one `stamp_ns` falls in: [k·period, (k+1)·period).
/// A reader that took a sample of the window has no other of it to wait for.
std::int64_t simPeriodWindowEnd(std::int64_t stamp_ns, std::int64_t period_ns);

/// Which samples a period lets through: of each vehicle, the first one stamped in each window
/// [k·period, (k+1)·period) of sim time, in the order they are offered, and again any sample
/// stamped as the last one passed (a writer sending one again: a lockstep plant resends its
/// clock while it waits, and a reader that matched late takes the resend). Another sample in
/// the window of the last one passed goes; any other window (one later, or earlier: a clock
/// that started again) opens anew. Thread-safe.
class SimPeriodGate {
public:
  explicit SimPeriodGate(std::int64_t period_ns);
  std::int64_t period() const { return period_ns_; }
  bool pass(std::uint32_t vehicle_id, std::int64_t stamp_ns);

private:
  std::int64_t period_ns_;
  std::mutex mutex_;
  struct Passed {
    std::int64_t window;
    std::int64_t stamp_ns;
  };
  std::map<std::uint32_t, Passed> passed_;  // vehicle -> the last one passed
};

/// The factory every quad participant registers under kSimPeriodFilterClass. A payload without
/// a readable Header (a display schema) always passes.
eprosima::fastdds::dds::IContentFilterFactory& simPeriodFilterFactory();

/// `qos` asking for at most one sample per `period_ns` of sim time, by the filter above, its
/// deadline widened to two periods if it was shorter; 0 asks for every sample.
eprosima::fastdds::dds::DataReaderQos withMinimumSeparation(eprosima::fastdds::dds::DataReaderQos qos,
                                                            std::int64_t period_ns);
/// The minimum separation `qos` asks for [ns]; 0 for none.
std::int64_t minimumSeparationNs(const eprosima::fastdds::dds::DataReaderQos& qos);

}  // namespace quad::dds
