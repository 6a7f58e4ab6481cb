// SPDX-License-Identifier: BSD-3-Clause
#include "quad/dds/endpoint.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "quad/common/digest.hpp"
#include "quad/common/time.hpp"
#include "quad/dds/sim_period_filter.hpp"

namespace quad::dds {

namespace fdds = eprosima::fastdds::dds;

namespace {
std::string incompatibleText(const char* side, fdds::QosPolicyId_t policy, std::uint32_t total)
{
  return std::string(side) + " QoS policy " + qosPolicyName(static_cast<std::uint32_t>(policy)) +
         " is incompatible with a remote endpoint (" + std::to_string(total) + " so far)";
}

std::optional<std::int64_t> leaseNs(const eprosima::fastrtps::Duration_t& lease)
{
  if (lease == eprosima::fastrtps::c_TimeInfinite) {
    return std::nullopt;
  }
  return lease.to_ns();
}

/// A writer's instance handle is its 16-byte GUID; fold it into 64 bits.
std::uint64_t writerId(const fdds::InstanceHandle_t& handle)
{
  const unsigned char* guid = handle.value;  // its 16 octets
  return common::digest(std::as_bytes(std::span(guid, 16)));
}
}  // namespace

// Listener callbacks run on Fast DDS threads: they count, push an event and return.
class WriterEndpoint::Listener : public fdds::DataWriterListener {
public:
  explicit Listener(WriterEndpoint& owner) : owner_(owner) {}

  void on_publication_matched(fdds::DataWriter*, const fdds::PublicationMatchedStatus& s) override
  {
    owner_.matched_ = s.current_count;
    owner_.peers_.update(s.last_subscription_handle.value, s.current_count_change);
    push(s.current_count_change > 0 ? EventKind::kMatched : EventKind::kUnmatched,
         "writer now matches " + std::to_string(s.current_count) + " reader(s)");
  }
  void on_offered_deadline_missed(fdds::DataWriter*, const fdds::OfferedDeadlineMissedStatus& s) override
  {
    push(EventKind::kDeadlineMissed,
         "writer missed its offered deadline (" + std::to_string(s.total_count) + " so far)");
  }
  void on_offered_incompatible_qos(fdds::DataWriter*, const fdds::OfferedIncompatibleQosStatus& s) override
  {
    push(EventKind::kIncompatibleQos, incompatibleText("offered", s.last_policy_id, s.total_count));
  }
  void on_liveliness_lost(fdds::DataWriter*, const fdds::LivelinessLostStatus& s) override
  {
    push(EventKind::kLivelinessLost,
         "writer failed to assert liveliness (" + std::to_string(s.total_count) + " so far)");
  }

private:
  void push(EventKind kind, std::string detail)
  {
    owner_.participant_.events().push({kind, std::string(owner_.info_.name), std::move(detail)});
  }
  WriterEndpoint& owner_;
};

WriterEndpoint::WriterEndpoint(Participant& participant, const TopicInfo& info,
                               const fdds::TypeSupport& type, std::optional<fdds::DataWriterQos> qos,
                               std::optional<std::uint32_t> partition)
    : participant_(participant),
      info_(info),
      listener_(std::make_unique<Listener>(*this)),
      publisher_(participant.publisher(partition))
{
  auto* topic = participant_.topic(info_, type);
  const fdds::DataWriterQos writer_qos = qos ? *qos : participant_.writerQos(info_);
  participant_.addLocalEndpoint(std::string(info_.name), type.get_type_name(),
                                type->m_isGetKeyDefined, true);
  writer_ = publisher_->create_datawriter(topic, writer_qos, listener_.get(), fdds::StatusMask::all());
  if (writer_ == nullptr) {
    participant_.removeLocalEndpoint(std::string(info_.name), true);
    throw std::runtime_error("cannot create writer on " + std::string(info_.name) + " (QoS profile " +
                             std::string(info_.qos_profile) + ".writer" +
                             (participant_.options().security_dir.empty()
                                  ? ")"
                                  : "; with security on, do its permissions grant publishing it?)"));
  }
}

WriterEndpoint::~WriterEndpoint()
{
  writer_->set_listener(nullptr);
  publisher_->delete_datawriter(writer_);
  participant_.removeLocalEndpoint(std::string(info_.name), true);
}

bool WriterEndpoint::writeSample(void* sample)
{
  if (writer_->write(sample)) {
    ++written_;
    return true;
  }
  const auto failures = ++failed_;
  participant_.events().push({EventKind::kWriteFailed, std::string(info_.name),
                              "write refused (" + std::to_string(failures) + " so far)"});
  return false;
}

std::optional<std::int64_t> WriterEndpoint::livelinessLeaseNs() const
{
  return leaseNs(writer_->get_qos().liveliness().lease_duration);
}

void WriterEndpoint::assertLiveliness()
{
  if (writer_->get_qos().liveliness().kind == fdds::MANUAL_BY_TOPIC_LIVELINESS_QOS) {
    writer_->assert_liveliness();
  }
}

void MatchedPeers::update(const std::uint8_t* guid, int change)
{
  std::array<std::uint8_t, 16> g;
  std::copy_n(guid, g.size(), g.begin());
  std::lock_guard lock(mutex_);
  const auto it = std::find(guids_.begin(), guids_.end(), g);
  if (change > 0 && it == guids_.end()) {
    guids_.push_back(g);
  } else if (change < 0 && it != guids_.end()) {
    guids_.erase(it);
  }
}

std::vector<ParticipantPrefix> MatchedPeers::participants() const
{
  std::lock_guard lock(mutex_);
  std::vector<ParticipantPrefix> out;
  for (const auto& g : guids_) {
    ParticipantPrefix p;
    std::copy_n(g.begin(), p.size(), p.begin());  // the prefix; the entity id follows
    out.push_back(p);
  }
  return out;
}

bool WriterEndpoint::waitForAcknowledgments(std::chrono::milliseconds timeout)
{
  const auto ms = timeout.count();
  const eprosima::fastrtps::Duration_t max_wait(static_cast<std::int32_t>(ms / 1000),
                                                static_cast<std::uint32_t>((ms % 1000) * 1'000'000));
  return writer_->wait_for_acknowledgments(max_wait) == ReturnCode_t::RETCODE_OK;
}

class ReaderEndpoint::Listener : public fdds::DataReaderListener {
public:
  Listener(ReaderEndpoint& owner, Waker* waker) : owner_(owner), waker_(waker) {}

  void on_data_available(fdds::DataReader*) override
  {
    told_of_data_.store(true, std::memory_order_release);
    if (waker_ != nullptr) {
      waker_->notify();
    }
  }
  void on_subscription_matched(fdds::DataReader*, const fdds::SubscriptionMatchedStatus& s) override
  {
    owner_.matched_ = s.current_count;
    owner_.peers_.update(s.last_publication_handle.value, s.current_count_change);
    push(s.current_count_change > 0 ? EventKind::kMatched : EventKind::kUnmatched,
         "reader now matches " + std::to_string(s.current_count) + " writer(s)");
  }
  void on_requested_deadline_missed(fdds::DataReader*,
                                    const fdds::RequestedDeadlineMissedStatus& s) override
  {
    owner_.deadlines_missed_ = static_cast<std::uint64_t>(s.total_count);
    push(EventKind::kDeadlineMissed,
         "no sample within the deadline (" + std::to_string(s.total_count) + " so far)");
  }
  void on_liveliness_changed(fdds::DataReader*, const fdds::LivelinessChangedStatus& s) override
  {
    // alive +1: (again) alive; not alive +1: lost its lease; alive -1 alone: went away.
    if (s.alive_count_change != 0 || s.not_alive_count_change != 0) {
      const bool alive = s.alive_count_change > 0;
      std::lock_guard<std::mutex> lock(owner_.liveliness_mutex_);
      owner_.liveliness_changes_.push_back({writerId(s.last_publication_handle), alive, common::steadyTimeNs()});
    }
    if (s.not_alive_count_change > 0) {
      push(EventKind::kLivelinessLost,
           "a writer lost liveliness; " + std::to_string(s.alive_count) + " alive");
    } else if (s.alive_count_change > 0 && s.not_alive_count_change < 0) {
      push(EventKind::kLivelinessRegained,
           "a writer is alive again; " + std::to_string(s.alive_count) + " alive");
    }
  }
  void on_sample_rejected(fdds::DataReader*, const fdds::SampleRejectedStatus& s) override
  {
    push(EventKind::kSampleRejected,
         "sample rejected by resource limits (" + std::to_string(s.total_count) + " so far)");
  }
  void on_requested_incompatible_qos(fdds::DataReader*,
                                     const fdds::RequestedIncompatibleQosStatus& s) override
  {
    push(EventKind::kIncompatibleQos,
         incompatibleText("requested", s.last_policy_id, s.total_count));
  }
  void on_sample_lost(fdds::DataReader*, const fdds::SampleLostStatus& s) override
  {
    push(EventKind::kSampleLost, std::to_string(s.total_count) + " sample(s) lost so far", s.total_count_change);
  }

  /// Whether on_data_available has been called: Fast DDS has counted an instance's sample.
  bool toldOfData() const { return told_of_data_.load(std::memory_order_acquire); }

private:
  void push(EventKind kind, std::string detail, std::int64_t count = 0)
  {
    owner_.participant_.events().push({kind, std::string(owner_.info_.name), std::move(detail), count});
  }
  ReaderEndpoint& owner_;
  Waker* waker_;
  std::atomic<bool> told_of_data_{false};
};

ReaderEndpoint::ReaderEndpoint(Participant& participant, const TopicInfo& info,
                               const fdds::TypeSupport& type, Waker* waker,
                               std::optional<fdds::DataReaderQos> qos, std::optional<std::uint32_t> partition)
    : participant_(participant),
      info_(info),
      listener_(std::make_unique<Listener>(*this, waker)),
      subscriber_(participant.subscriber(partition))
{
  fdds::DataReaderQos reader_qos = qos ? *qos : participant_.readerQos(info_);
  // A minimum separation is kept in sim time by a content filter (sim_period_filter.hpp), not
  // asked of Fast DDS, which would not keep it.
  topic_ = participant_.readerTopic(info_, type, minimumSeparationNs(reader_qos));
  reader_qos = withMinimumSeparation(std::move(reader_qos), 0);
  participant_.addLocalEndpoint(std::string(info_.name), type.get_type_name(),
                                type->m_isGetKeyDefined, false);
  reader_ = subscriber_->create_datareader(topic_, reader_qos, listener_.get(), fdds::StatusMask::all());
  if (reader_ == nullptr) {
    participant_.removeLocalEndpoint(std::string(info_.name), false);
    participant_.releaseReaderTopic(topic_);
    throw std::runtime_error("cannot create reader on " + std::string(info_.name) + " (QoS profile " +
                             std::string(info_.qos_profile) + ".reader" +
                             (participant_.options().security_dir.empty()
                                  ? ")"
                                  : "; with security on, do its permissions grant subscribing to it?)"));
  }
}

ReaderEndpoint::~ReaderEndpoint()
{
  reader_->set_listener(nullptr);
  subscriber_->delete_datareader(reader_);
  participant_.releaseReaderTopic(topic_);
  participant_.removeLocalEndpoint(std::string(info_.name), false);
}

std::optional<std::int64_t> ReaderEndpoint::livelinessLeaseNs() const
{
  return leaseNs(reader_->get_qos().liveliness().lease_duration);
}

std::vector<ReaderEndpoint::WriterLiveliness> ReaderEndpoint::takeLivelinessChanges()
{
  std::lock_guard<std::mutex> lock(liveliness_mutex_);
  return std::exchange(liveliness_changes_, {});
}

bool ReaderEndpoint::ownVehicle(std::uint32_t vehicle_id)
{
  const std::uint32_t own = participant_.options().vehicle_id;
  return servedVehicle(vehicle_id, std::span<const std::uint32_t>(&own, 1));
}

bool ReaderEndpoint::servedVehicle(std::uint32_t vehicle_id, std::span<const std::uint32_t> served)
{
  if (std::find(served.begin(), served.end(), vehicle_id) != served.end()) {
    return true;
  }
  const std::uint64_t n = ++foreign_;
  if ((n & (n - 1)) == 0) {
    std::string serving;
    for (const std::uint32_t id : served) {
      serving += (serving.empty() ? "" : ", ") + std::to_string(id);
    }
    participant_.events().push({EventKind::kForeignSample, std::string(info_.name),
                                "sample for vehicle " + std::to_string(vehicle_id) + " ignored (" +
                                    (served.size() == 1 ? "this is vehicle " : "this serves vehicles ") + serving +
                                    "; " + std::to_string(n) + " so far)"});
  }
  return false;
}

bool ReaderEndpoint::takeSample(void* sample, std::uint64_t* writer, std::int64_t* received_ns)
{
  if (!listener_->toldOfData()) {
    return false;
  }
  fdds::SampleInfo info;
  while (reader_->take_next_sample(sample, &info) == ReturnCode_t::RETCODE_OK) {
    if (info.valid_data) {
      if (writer != nullptr) {
        *writer = writerId(info.publication_handle);
      }
      if (received_ns != nullptr) {
        *received_ns = info.reception_timestamp.to_ns();
      }
      return true;
    }
  }
  return false;
}

}  // namespace quad::dds
