#pragma once
/// @file
/// A typed reader on a topic contract.

#include <optional>
#include <vector>

#include "quad/dds/endpoint.hpp"

namespace quad::dds {

/// Takes samples of one topic. Arrivals notify the given Waker (the node's loop); statuses
/// go to the participant's event queue.
template <class Message>
class Subscriber : public ReaderEndpoint {
public:
  Subscriber(Participant& participant, const Topic<Message>& topic, Waker* waker = nullptr,
             std::optional<eprosima::fastdds::dds::DataReaderQos> qos = std::nullopt)
      : ReaderEndpoint(participant, topic.info,
                       eprosima::fastdds::dds::TypeSupport(
                           new typename MessageTraits<Message>::PubSubType()),
                       waker, std::move(qos))
  {
  }

  /// The next unread sample, if any.
  std::optional<Message> take()
  {
    Message sample;
    if (takeSample(&sample)) {
      return sample;
    }
    return std::nullopt;
  }

  /// Every unread sample, oldest first.
  std::vector<Message> takeAll()
  {
    std::vector<Message> out;
    for (Message sample; takeSample(&sample);) {
      out.push_back(sample);
    }
    return out;
  }
};

}  // namespace quad::dds
