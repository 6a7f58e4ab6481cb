// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The shape of a topic contract: what every topic declares once.

#include <cstdint>
#include <string_view>

#include "quad/dds/message_types.hpp"

namespace quad::dds {

/// The module that owns (writes) a topic.
enum class Owner { kPlant, kEstimation, kMapping, kPlanning, kControl, kDisplay, kOperator, kFaultTool, kEveryModule };

std::string_view toString(Owner owner);

/// A topic contract without its C++ type: what tools (topic list, the recorder) iterate over.
struct TopicInfo {
  std::string_view name;         ///< quad/<function>/<name>
  std::string_view type_name;    ///< registered DDS type name, e.g. quad::msg::VehicleState
  std::string_view idl_file;     ///< IDL file of the type, relative to idl/
  std::string_view qos_profile;  ///< QoS class in configs/dds/quad_qos.xml (<class>.writer/.reader)
  double rate_hz;                ///< expected rate; 0 for event-driven topics
  Owner owner;
  std::string_view description;
  /// Largest serialized sample, encapsulation included [bytes]: sizes type-agnostic readers.
  std::uint32_t (*max_serialized_size)() = nullptr;
  /// The deadline: a reader judges the topic stale once its newest sample is older than this
  /// (in sim time) [s]; its writers publish, or republish, well within it. 0: not judged.
  double stale_after_s = 0.0;
  /// The type leads with quad's Header (stamp, per-writer seq, the vehicle as its key); the
  /// display topics' Foxglove schemas do not.
  bool has_header = true;
};

/// A typed topic contract. Publisher<T> and Subscriber<T> accept only a Topic<T>, so a topic
/// with the wrong message type, or a misspelt topic, fails to compile.
template <class Message>
struct Topic {
  using MessageType = Message;
  TopicInfo info;
};

/// Builds a contract whose type name and IDL file come from the message type itself.
template <class Message>
constexpr Topic<Message> makeTopic(std::string_view name, std::string_view qos_profile,
                                   double rate_hz, Owner owner, std::string_view description,
                                   double stale_after_s = 0.0)
{
  return Topic<Message>{TopicInfo{name, MessageTraits<Message>::kTypeName,
                                  MessageTraits<Message>::kIdlFile, qos_profile, rate_hz, owner,
                                  description, &MessageTraits<Message>::maxSerializedSize, stale_after_s,
                                  MessageTraits<Message>::kHasHeader}};
}

}  // namespace quad::dds
