// SPDX-License-Identifier: BSD-3-Clause
#include "quad/wire/fault_transport.hpp"

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <queue>
#include <thread>
#include <vector>

#include <fastdds/rtps/transport/ChainingTransportDescriptor.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>

#include "quad/common/time.hpp"
#include "receive_layer.hpp"

namespace quad::wire {

namespace frtps = eprosima::fastrtps::rtps;
namespace fdrtps = eprosima::fastdds::rtps;

namespace {

class FaultyTransportDescriptor : public fdrtps::ChainingTransportDescriptor {
public:
  FaultyTransportDescriptor(std::shared_ptr<DatagramFaults> faults,
                            std::shared_ptr<fdrtps::TransportDescriptorInterface> udp)
      : ChainingTransportDescriptor(std::move(udp)), faults_(std::move(faults))
  {
  }

  fdrtps::TransportInterface* create_transport() const override;

private:
  std::shared_ptr<DatagramFaults> faults_;
};

/// Applies fates on reception. Datagrams that go through untouched are handed on from the
/// receive thread; delayed ones from a thread of the layer's own. One mutex serialises every
/// hand-on, because Fast DDS's receivers expect one thread per channel.
class FaultyTransport : public ReceiveLayer {
public:
  FaultyTransport(const FaultyTransportDescriptor& d, std::shared_ptr<DatagramFaults> faults)
      : ReceiveLayer(d), descriptor_(d), faults_(std::move(faults))
  {
    thread_ = std::thread([this] { deliverDelayed(); });
  }

  ~FaultyTransport() override
  {
    {
      std::lock_guard lock(queue_mutex_);
      quit_ = true;
    }
    queue_cv_.notify_all();
    thread_.join();
  }

  fdrtps::TransportDescriptorInterface* get_configuration() override { return &descriptor_; }

  bool CloseInputChannel(const frtps::Locator_t& loc) override
  {
    const bool closed = ChainingTransport::CloseInputChannel(loc);
    {
      std::lock_guard lock(queue_mutex_);
      std::vector<Delayed> keep;
      while (!queue_.empty()) {
        if (queue_.top().local != loc) {
          keep.push_back(queue_.top());
        }
        queue_.pop();
      }
      for (auto& d : keep) {
        queue_.push(std::move(d));
      }
    }
    std::lock_guard wait_for_hand_on(deliver_mutex_);
    return closed;
  }

  void receive(fdrtps::TransportReceiverInterface* next_receiver, const frtps::octet* receive_buffer,
               uint32_t receive_buffer_size, const frtps::Locator_t& local_locator,
               const frtps::Locator_t& remote_locator) override
  {
    const DatagramFate fate = faults_->fate(receive_buffer, receive_buffer_size);
    if (fate.drop) {
      return;
    }
    if (fate.untouched()) {
      std::lock_guard lock(deliver_mutex_);
      next_receiver->OnDataReceived(receive_buffer, receive_buffer_size, local_locator, remote_locator);
      return;
    }
    std::vector<frtps::octet> bytes(receive_buffer, receive_buffer + receive_buffer_size);
    if (fate.corrupt) {
      bytes[*fate.corrupt] ^= static_cast<frtps::octet>(1U << fate.corrupt_bit);
    }
    if (fate.delay_ns == 0) {
      std::lock_guard lock(deliver_mutex_);
      for (int i = 0; i < fate.copies; ++i) {
        next_receiver->OnDataReceived(bytes.data(), static_cast<uint32_t>(bytes.size()), local_locator,
                                      remote_locator);
      }
      return;
    }
    {
      std::lock_guard lock(queue_mutex_);
      queue_.push(Delayed{common::steadyTimeNs() + fate.delay_ns, ++order_, std::move(bytes), fate.copies,
                          next_receiver, local_locator, remote_locator});
    }
    queue_cv_.notify_all();
  }

private:
  struct Delayed {
    std::int64_t due_ns;
    std::uint64_t order;  // FIFO among datagrams due at the same time
    std::vector<frtps::octet> bytes;
    int copies;
    fdrtps::TransportReceiverInterface* receiver;
    frtps::Locator_t local;
    frtps::Locator_t remote;
  };
  struct Later {
    bool operator()(const Delayed& a, const Delayed& b) const
    {
      return a.due_ns != b.due_ns ? a.due_ns > b.due_ns : a.order > b.order;
    }
  };

  void deliverDelayed()
  {
    std::unique_lock lock(queue_mutex_);
    while (!quit_) {
      if (queue_.empty()) {
        queue_cv_.wait(lock);
        continue;
      }
      const std::int64_t wait_ns = queue_.top().due_ns - common::steadyTimeNs();
      if (wait_ns > 0) {
        queue_cv_.wait_for(lock, std::chrono::nanoseconds(wait_ns));
        continue;
      }
      Delayed d = queue_.top();
      queue_.pop();
      // Taken before the queue is let go, so that CloseInputChannel cannot return between
      // this datagram leaving the queue and reaching its receiver.
      std::lock_guard deliver(deliver_mutex_);
      lock.unlock();
      for (int i = 0; i < d.copies; ++i) {
        d.receiver->OnDataReceived(d.bytes.data(), static_cast<uint32_t>(d.bytes.size()), d.local, d.remote);
      }
      lock.lock();
    }
  }

  FaultyTransportDescriptor descriptor_;
  std::shared_ptr<DatagramFaults> faults_;
  std::mutex deliver_mutex_;
  std::mutex queue_mutex_;
  std::condition_variable queue_cv_;
  std::priority_queue<Delayed, std::vector<Delayed>, Later> queue_;
  std::uint64_t order_ = 0;
  bool quit_ = false;
  std::thread thread_;
};

fdrtps::TransportInterface* FaultyTransportDescriptor::create_transport() const
{
  return new FaultyTransport(*this, faults_);
}

}  // namespace

std::shared_ptr<fdrtps::TransportDescriptorInterface> faultyUdpTransport(
    std::shared_ptr<DatagramFaults> faults, std::shared_ptr<fdrtps::TransportDescriptorInterface> udp)
{
  return std::make_shared<FaultyTransportDescriptor>(std::move(faults), std::move(udp));
}

}  // namespace quad::wire
