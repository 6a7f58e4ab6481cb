// SPDX-License-Identifier: BSD-3-Clause
#include "quad/wire/validating_transport.hpp"

#include <atomic>
#include <mutex>

#include <fastdds/rtps/transport/ChainingTransportDescriptor.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "quad/common/time.hpp"
#include "quad/wire/count_guard.hpp"
#include "quad/wire/rtps_check.hpp"
#include "quad/wire/sequence_guard.hpp"
#include "receive_layer.hpp"

namespace quad::wire {

namespace frtps = eprosima::fastrtps::rtps;
namespace fdrtps = eprosima::fastdds::rtps;

namespace {

constexpr std::int64_t kLogPeriodNs = 1'000'000'000;  // at most one log line a second

std::atomic<std::uint64_t> checked_count{0};
std::atomic<std::uint64_t> malformed_count{0};
std::mutex malformed_mutex;
MalformedDatagrams malformed;
std::int64_t next_log_ns = 0;
std::uint64_t logged_count = 0;

/// "127.0.0.1:41234"
std::string addressOf(const frtps::Locator_t& from)
{
  return fmt::format("{}.{}.{}.{}:{}", from.address[12], from.address[13], from.address[14], from.address[15],
                     from.port);
}

void noteMalformed(const frtps::Locator_t& from, std::uint32_t size, const RtpsDefect& d)
{
  const std::string what = fmt::format("from {}, {} bytes: at byte {}: {}", addressOf(from), size, d.offset, d.what);
  std::lock_guard lock(malformed_mutex);
  ++malformed.count;
  malformed.last = what;
  malformed_count.store(malformed.count, std::memory_order_relaxed);
  const std::int64_t now = common::steadyTimeNs();
  if (now >= next_log_ns) {
    spdlog::warn("malformed RTPS datagram dropped ({} since the last report): {}", malformed.count - logged_count,
                 what);
    logged_count = malformed.count;
    next_log_ns = now + kLogPeriodNs;
  }
}

std::atomic<std::uint64_t> tamed_count{0};
std::int64_t next_tamed_log_ns = 0;

void noteTamed(const frtps::Locator_t& from, const CountGuard::Taming& t)
{
  tamed_count.fetch_add(1, std::memory_order_relaxed);
  std::lock_guard lock(malformed_mutex);
  const std::int64_t now = common::steadyTimeNs();
  if (t.first) {
    // What joining a running stack looks like (a writer's counts began at its start): no warning.
    spdlog::debug("RTPS count from {} starts at {}: passed on as {}", addressOf(from), t.count.count, t.replaced);
  } else if (now >= next_tamed_log_ns) {
    spdlog::warn("RTPS count from {} leaps to {}: passed on as {} ({} so far)", addressOf(from), t.count.count,
                 t.replaced, tamed_count.load(std::memory_order_relaxed));
    next_tamed_log_ns = now + kLogPeriodNs;
  }
}

class ValidatingTransportDescriptor : public fdrtps::ChainingTransportDescriptor {
public:
  explicit ValidatingTransportDescriptor(std::shared_ptr<fdrtps::TransportDescriptorInterface> inner)
      : ChainingTransportDescriptor(std::move(inner))
  {
  }

  fdrtps::TransportInterface* create_transport() const override;
};

class ValidatingTransport : public ReceiveLayer {
public:
  explicit ValidatingTransport(const ValidatingTransportDescriptor& d) : ReceiveLayer(d), descriptor_(d) {}

  fdrtps::TransportDescriptorInterface* get_configuration() override { return &descriptor_; }

  void receive(fdrtps::TransportReceiverInterface* next_receiver, const frtps::octet* receive_buffer,
               uint32_t receive_buffer_size, const frtps::Locator_t& local_locator,
               const frtps::Locator_t& remote_locator) override
  {
    checked_count.fetch_add(1, std::memory_order_relaxed);
    thread_local std::vector<RtpsCount> counts;
    thread_local std::vector<RtpsSequence> sequences;
    counts.clear();
    sequences.clear();
    if (const auto defect = checkRtpsDatagram(receive_buffer, receive_buffer_size, &counts, &sequences)) {
      noteMalformed(remote_locator, receive_buffer_size, *defect);
      return;
    }
    const std::int64_t now = common::steadyTimeNs();
    if (const auto leap = sequences_.admit(sequences, now)) {
      noteMalformed(remote_locator, receive_buffer_size, *leap);
      return;
    }
    const auto tamings = counts_.admit(counts, now);
    if (!tamings.empty()) {
      // Passed on, with each leaping count lowered (count_guard.hpp).
      thread_local std::vector<frtps::octet> copy;
      copy.assign(receive_buffer, receive_buffer + receive_buffer_size);
      CountGuard::apply(tamings, copy.data());
      noteTamed(remote_locator, tamings.front());
      next_receiver->OnDataReceived(copy.data(), receive_buffer_size, local_locator, remote_locator);
      return;
    }
    next_receiver->OnDataReceived(receive_buffer, receive_buffer_size, local_locator, remote_locator);
  }

private:
  ValidatingTransportDescriptor descriptor_;
  CountGuard counts_;  // per participant, as the counts a receiver keeps
  SequenceGuard sequences_;
};

fdrtps::TransportInterface* ValidatingTransportDescriptor::create_transport() const
{
  return new ValidatingTransport(*this);
}

}  // namespace

std::shared_ptr<fdrtps::TransportDescriptorInterface> validatingTransport(
    std::shared_ptr<fdrtps::TransportDescriptorInterface> inner)
{
  return std::make_shared<ValidatingTransportDescriptor>(std::move(inner));
}

MalformedDatagrams malformedDatagrams()
{
  std::lock_guard lock(malformed_mutex);
  MalformedDatagrams m = malformed;
  m.checked = checked_count.load(std::memory_order_relaxed);
  return m;
}

std::uint64_t malformedDatagramCount()
{
  return malformed_count.load(std::memory_order_relaxed);
}

}  // namespace quad::wire
