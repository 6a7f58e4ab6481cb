#include "quad/dds/validating_transport.hpp"

#include <atomic>
#include <mutex>

#include <fastdds/rtps/transport/ChainingTransportDescriptor.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "quad/common/time.hpp"
#include "receive_layer.hpp"
#include "quad/dds/rtps_check.hpp"

namespace quad::dds {

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

void noteMalformed(const frtps::Locator_t& from, std::uint32_t size, const RtpsDefect& d)
{
  const std::string what = fmt::format("from {}.{}.{}.{}:{}, {} bytes: at byte {}: {}", from.address[12],
                                       from.address[13], from.address[14], from.address[15], from.port, size,
                                       d.offset, d.what);
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
    if (const auto defect = checkRtpsDatagram(receive_buffer, receive_buffer_size)) {
      noteMalformed(remote_locator, receive_buffer_size, *defect);
      return;
    }
    next_receiver->OnDataReceived(receive_buffer, receive_buffer_size, local_locator, remote_locator);
  }

private:
  ValidatingTransportDescriptor descriptor_;
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

}  // namespace quad::dds
