// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// One DDS participant per process, with quad's QoS profiles, transports and discovery, and
/// each node's handle on it: a process that hosts several nodes (a container) shares one
/// participant among them (two in one process can deadlock, intraprocessDeliveryOff()).

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "quad/wire/datagram_faults.hpp"
#include "quad/dds/events.hpp"
#include "quad/dds/topic.hpp"

namespace quad::dds {

enum class Transport {
  kDefault,       ///< Fast DDS's builtin transports: UDPv4, plus shared memory between local peers
  kUdp,           ///< UDPv4 only, data-sharing off: every sample crosses the network stack
  kSharedMemory,  ///< shared memory only: local processes only
};

struct ParticipantOptions {
  std::string name;       ///< participant name, shown by `quad topic list`
  int domain_id = 0;      ///< 0..232
  Transport transport = Transport::kDefault;
  std::vector<std::string> initial_peers;  ///< "IP" or "IP:PORT" unicast discovery peers
  std::string discovery_server;            ///< "IP:PORT" of a Fast DDS discovery server (id 0)
  /// UDP on these IPv4 addresses of this host only (Fast DDS's interface whitelist: sockets
  /// bound to them, nothing sent or received on other interfaces); empty: every interface.
  std::vector<std::string> interfaces;
  /// With a discovery server: learn every endpoint of the domain (a SUPER_CLIENT), not only
  /// those matching this participant's own. Tools that watch the whole graph set it.
  bool observe_all = false;
  std::filesystem::path qos_file;          ///< QoS profiles XML; empty: the installed default
  std::uint32_t vehicle_id = 0;            ///< written into Header.vehicle_id of every sample
  /// Received datagrams pass a fault layer (datagram_faults.hpp) in front of UDP, so that
  /// fault injection can break this participant's links. Implies UDP only, data-sharing off
  /// and, for the whole process, intraprocess delivery off: each would go around the layer.
  bool fault_layer = false;
  /// UDP only: the largest datagram Fast DDS sends, in bytes; larger samples go as RTPS
  /// fragments, each repaired on its own. 0: Fast DDS's default (65500), which over a real
  /// link is ~45 IP fragments, all lost when one is.
  std::uint32_t udp_max_message = 0;
  /// Received UDP datagrams pass the validating transport (validating_transport.hpp), which
  /// drops malformed ones before Fast DDS parses them. Shared memory, which only local
  /// processes reach, is not checked.
  bool validate_datagrams = true;
  /// Readers expect inline QoS, so writers send each sample's key hash and the validating
  /// transport refuses a sample whose payload holds another key (rtps_check.hpp). Off by
  /// default: Cyclone DDS matches no such reader, and with it on a lockstep replay of the
  /// demo's controller parted from its run at start-up in two CI runs of three.
  bool inline_keys = false;
  /// DDS Security on: authentication, access control and encryption with the files of
  /// `quad security init` in this folder (security.hpp). Empty: off.
  std::filesystem::path security_dir;
  /// The identity in `security_dir` to use; empty: securityIdentity(name).
  std::string security_identity;
  /// The run's sim clock is a lockstep one: a node follows lockstep's rules from its start,
  /// so that an input reaching it before the clock's first sample (a latched goal) is taken
  /// as it would be after. The clock's samples still say which mode runs.
  bool lockstep = false;
  /// A lockstep run's recorder takes part in its start: the clock owner does not step past
  /// its first round until the recorder reads every topic it writes (recorder.hpp), so a
  /// recording holds the run from sim time 0, as a replay needs.
  bool lockstep_recorder = false;
  /// A lockstep run's observer (the launcher's) takes part in its start as its recorder does:
  /// the clock owner does not step past its first round until the observer reads what it
  /// scores (observer.hpp), so a run's summary counts every state from sim time 0.
  bool lockstep_observer = false;
  /// How long other participants keep this one without hearing from it [s]; 0: the QoS
  /// profile's (2 s). Announcements stay as often as the profile says. A machine so loaded
  /// that a participant goes unheard for longer has its peers drop it, and Fast DDS 2.9 does
  /// not always match the endpoints again once it is heard (docs/fleet.md).
  int participant_lease_s = 0;
  /// The run's budget for a scan's map update in lockstep [ns]; none: the topic contract's
  /// (topics::kMapUpdateBudgetNs). The mapper and the planner of a run must agree on it.
  std::optional<std::int64_t> map_budget_ns;
  /// The map update's budget this run keeps: map_budget_ns, else the contract's.
  std::int64_t mapBudgetNs() const;
  /// The run's budget for a replan's path [ns]; none: the topic contract's
  /// (topics::kPathBudgetNs).
  std::optional<std::int64_t> path_budget_ns;
  /// The path's budget this run keeps: path_budget_ns, else the contract's.
  std::int64_t pathBudgetNs() const;
};

/// The options a quad process takes from its environment, so that every module and tool of a
/// run share one domain and discovery setup:
/// QUAD_DOMAIN_ID, QUAD_TRANSPORT (default|udp|shm), QUAD_INITIAL_PEERS (comma separated),
/// QUAD_DISCOVERY_SERVER, QUAD_QOS_FILE, QUAD_VEHICLE_ID, QUAD_FAULT_LAYER (0|1),
/// QUAD_UDP_MAX_MESSAGE (bytes), QUAD_VALIDATE_DATAGRAMS (0|1), QUAD_SECURITY_DIR,
/// QUAD_SECURITY_IDENTITY, QUAD_LOCKSTEP (0|1), QUAD_PARTICIPANT_LEASE (whole seconds),
/// QUAD_MAP_BUDGET_MS and QUAD_PATH_BUDGET_MS (whole milliseconds, 0 to 1000). A bad value throws
/// std::invalid_argument naming the variable and the value.
ParticipantOptions optionsFromEnvironment(std::string name);

/// Turns Fast DDS's intraprocess delivery off for the whole process, for the participants
/// created after the call. Needed where samples must cross a transport layer (the fault
/// layer), and in every process that holds two participants: Fast DDS 2.9 delivers a
/// liveliness assertion to the other participant's reader from its event thread while that
/// participant's receive threads wait for the same locks the other way round, and the process
/// deadlocks (it hears nothing more and hangs at exit).
void intraprocessDeliveryOff();

/// Parses a transport name: "default", "udp" or "shm".
Transport parseTransport(std::string_view text);

/// The QoS profiles file used when none is given: $QUAD_QOS_FILE, else configs/dds/quad_qos.xml.
std::filesystem::path defaultQosFile();

/// A remote reader or writer seen through discovery.
struct RemoteEndpoint {
  std::string guid;
  std::string topic;
  std::string type_name;
  bool keyed = false;
  bool writer = false;
  bool reliable = false;
  bool transient_local = false;
  std::string participant;  ///< the name of the participant it belongs to, when discovered
  std::string host;         ///< that participant's unicast addresses ("10.77.0.2, 127.0.0.1")
};

/// The DDS partitions that keep a fleet's vehicles apart: a participant of vehicle N ≥ 1
/// (QUAD_VEHICLE_ID) publishes and subscribes in "vehicle.N" alone, so that one vehicle's
/// samples never reach another's modules; any other (vehicle 0: a lone vehicle's modules, the
/// plant, the launcher, the tools) in "" and "*", which match the default partition and every
/// vehicle's. An endpoint may ask for another vehicle's (the plant writes each vehicle's
/// samples in that vehicle's) or for vehicle 0's, every vehicle (a planner reads every path).
std::vector<std::string> vehiclePartitions(std::uint32_t vehicle_id);
/// The partition of every vehicle (an endpoint's `partition`).
inline constexpr std::uint32_t kEveryVehicle = 0;

/// A process's DDS participant: owns the DomainParticipant, its Publishers and Subscribers,
/// registered types and topics, and what discovery saw. Creates everything in the
/// constructor and throws std::runtime_error naming what failed; the destructor deletes every
/// entity it created. The nodes of a process share it, each through a Participant.
class SharedParticipant {
public:
  explicit SharedParticipant(ParticipantOptions options);
  ~SharedParticipant();
  SharedParticipant(const SharedParticipant&) = delete;
  SharedParticipant& operator=(const SharedParticipant&) = delete;

  /// Deletes every entity and the participant now, as the destructor does unless this did:
  /// a process that ends without destroying its nodes removes its participant first, so that
  /// its peers see it leave at once. Nothing made through it may be used after.
  void close();

  const ParticipantOptions& options() const { return options_; }
  /// The faults on received datagrams; null without ParticipantOptions::fault_layer.
  wire::DatagramFaults* datagramFaults() { return datagram_faults_.get(); }
  const wire::DatagramFaults* datagramFaults() const { return datagram_faults_.get(); }

  /// Registers the type (once) and returns the topic (created once per name).
  eprosima::fastdds::dds::Topic* topic(const TopicInfo& info,
                                       const eprosima::fastdds::dds::TypeSupport& type);

  /// What a reader of `info` reads: the topic itself, or, with `period_ns` > 0, a topic of its
  /// own filtered to one sample per that much sim time (sim_period_filter.hpp). A filtered one
  /// is deleted by releaseReaderTopic once its reader is.
  eprosima::fastdds::dds::TopicDescription* readerTopic(const TopicInfo& info,
                                                        const eprosima::fastdds::dds::TypeSupport& type,
                                                        std::int64_t period_ns);
  void releaseReaderTopic(eprosima::fastdds::dds::TopicDescription* topic);

  /// The publisher, or subscriber, in the partitions of `vehicle` (vehiclePartitions), made
  /// on first use; without one, of the participant's own vehicle.
  eprosima::fastdds::dds::Publisher* publisher(std::optional<std::uint32_t> vehicle = std::nullopt);
  eprosima::fastdds::dds::Subscriber* subscriber(std::optional<std::uint32_t> vehicle = std::nullopt);
  eprosima::fastdds::dds::DomainParticipant* raw() { return participant_; }

  /// QoS of the named profile in the QoS file; throws naming the profile if it is missing.
  eprosima::fastdds::dds::DataWriterQos writerQos(std::string_view qos_class) const;
  eprosima::fastdds::dds::DataReaderQos readerQos(std::string_view qos_class) const;
  /// Writers of this QoS class promise every sample to every reader: reliable, KEEP_ALL
  /// (map changes). KEEP_LAST N promises the newest N only: a reader that falls N behind
  /// (a paused process) loses the older ones by contract.
  bool promisesEverySample(std::string_view qos_class) const;
  /// QoS of a topic's endpoints: its class's profile, and the contract's deadline
  /// (TopicInfo::stale_after_s) as the DDS DEADLINE: a reader asks for a sample within it
  /// (the middleware tells the node when none came: a deadline event), a writer offers it
  /// (or its class's tighter one), so the two match.
  eprosima::fastdds::dds::DataWriterQos writerQos(const TopicInfo& info) const;
  eprosima::fastdds::dds::DataReaderQos readerQos(const TopicInfo& info) const;

  /// Records a local endpoint so discovery can check remote ones against it; a remote one
  /// of another type is told to `events`, the queue of the node that owns the endpoint.
  void addLocalEndpoint(const std::string& topic, const std::string& type_name, bool keyed, bool writer,
                        std::shared_ptr<EventQueue> events);
  void removeLocalEndpoint(const std::string& topic, bool writer, const EventQueue* events);

  /// Remote endpoints discovered so far (alive ones only).
  std::vector<RemoteEndpoint> remoteEndpoints() const;

private:
  class Listener;
  /// Adds DDS Security's plugins and files (options_.security_dir) to `qos`; throws naming
  /// a file it cannot read.
  void enableSecurity(eprosima::fastdds::dds::DomainParticipantQos& qos) const;
  void onRemoteEndpoint(RemoteEndpoint endpoint, bool alive);
  struct RemoteParticipant {
    std::string name;
    std::string host;
  };
  void onRemoteParticipant(const std::string& prefix, RemoteParticipant participant, bool alive);
  void checkTypes(const RemoteEndpoint& remote);

  struct LocalEndpoint {
    std::string type_name;
    bool keyed;
    struct User {  // one per endpoint: the queue of its node (kept while told), and which side it is
      std::shared_ptr<EventQueue> events;
      bool writer;
    };
    std::vector<User> users;
  };

  ParticipantOptions options_;
  std::shared_ptr<wire::DatagramFaults> datagram_faults_;
  std::unique_ptr<Listener> listener_;
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* own_publisher_ = nullptr;    // in the participant's vehicle's partitions
  eprosima::fastdds::dds::Subscriber* own_subscriber_ = nullptr;
  std::mutex partitions_mutex_;
  std::map<std::uint32_t, eprosima::fastdds::dds::Publisher*> publishers_;    // by vehicle partition
  std::map<std::uint32_t, eprosima::fastdds::dds::Subscriber*> subscribers_;  // likewise
  std::map<std::string, eprosima::fastdds::dds::Topic*, std::less<>> topics_;
  std::uint64_t filtered_topics_ = 0;  // readerTopic's filtered ones made so far: their names

  mutable std::mutex endpoints_mutex_;
  std::map<std::string, LocalEndpoint, std::less<>> local_;
  std::map<std::string, RemoteEndpoint> remote_;  // by GUID
  std::map<std::string, RemoteParticipant> participants_;  // by GUID prefix
};

/// A node's handle on its process's participant: the DDS entities are shared, the endpoint
/// events are the node's own (each endpoint made through the handle tells its node). A
/// process of one node makes the participant with its handle; a container's other nodes join
/// it with theirs. Movable until an endpoint is made through it.
class Participant {
public:
  /// A participant of its own (made here, shared with handles made of shared()), whose
  /// node reports the process's refused inputs.
  explicit Participant(ParticipantOptions options);
  /// One more node on `shared`; throws std::invalid_argument without one.
  explicit Participant(std::shared_ptr<SharedParticipant> shared);
  Participant(Participant&&) noexcept = default;
  Participant& operator=(Participant&&) = delete;
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;
  ~Participant() = default;

  /// The DDS participant, to give another node of the process.
  const std::shared_ptr<SharedParticipant>& shared() const { return shared_; }
  /// This node's endpoint events.
  EventQueue& events() { return *events_; }
  /// Datagrams dropped are counted for the whole process (validating_transport.hpp): the node
  /// that made the participant reports them, no other.
  bool reportsProcessInputs() const { return reports_process_inputs_; }
  /// The types this node's readers take: a payload refused for breaking its IDL is counted
  /// by type for the process (message_types.hpp), and a node reports those of its own types.
  const std::set<std::string, std::less<>>& readerTypes() const { return reader_types_; }

  const ParticipantOptions& options() const { return shared_->options(); }
  wire::DatagramFaults* datagramFaults() { return shared_->datagramFaults(); }
  const wire::DatagramFaults* datagramFaults() const { return std::as_const(*shared_).datagramFaults(); }
  eprosima::fastdds::dds::Topic* topic(const TopicInfo& info, const eprosima::fastdds::dds::TypeSupport& type)
  {
    return shared_->topic(info, type);
  }
  eprosima::fastdds::dds::TopicDescription* readerTopic(const TopicInfo& info,
                                                        const eprosima::fastdds::dds::TypeSupport& type,
                                                        std::int64_t period_ns)
  {
    return shared_->readerTopic(info, type, period_ns);
  }
  void releaseReaderTopic(eprosima::fastdds::dds::TopicDescription* topic) { shared_->releaseReaderTopic(topic); }
  eprosima::fastdds::dds::Publisher* publisher(std::optional<std::uint32_t> vehicle = std::nullopt)
  {
    return shared_->publisher(vehicle);
  }
  eprosima::fastdds::dds::Subscriber* subscriber(std::optional<std::uint32_t> vehicle = std::nullopt)
  {
    return shared_->subscriber(vehicle);
  }
  eprosima::fastdds::dds::DomainParticipant* raw() { return shared_->raw(); }
  eprosima::fastdds::dds::DataWriterQos writerQos(std::string_view qos_class) const
  {
    return shared_->writerQos(qos_class);
  }
  eprosima::fastdds::dds::DataReaderQos readerQos(std::string_view qos_class) const
  {
    return shared_->readerQos(qos_class);
  }
  bool promisesEverySample(std::string_view qos_class) const { return shared_->promisesEverySample(qos_class); }
  eprosima::fastdds::dds::DataWriterQos writerQos(const TopicInfo& info) const { return shared_->writerQos(info); }
  eprosima::fastdds::dds::DataReaderQos readerQos(const TopicInfo& info) const { return shared_->readerQos(info); }
  void addLocalEndpoint(const std::string& topic, const std::string& type_name, bool keyed, bool writer)
  {
    if (!writer) {
      reader_types_.insert(type_name);
    }
    shared_->addLocalEndpoint(topic, type_name, keyed, writer, events_);
  }
  void removeLocalEndpoint(const std::string& topic, bool writer)
  {
    shared_->removeLocalEndpoint(topic, writer, events_.get());
  }
  std::vector<RemoteEndpoint> remoteEndpoints() const { return shared_->remoteEndpoints(); }

private:
  std::shared_ptr<SharedParticipant> shared_;
  std::shared_ptr<EventQueue> events_;
  bool reports_process_inputs_ = false;
  std::set<std::string, std::less<>> reader_types_;
};

/// `qos` keeping at least `depth` samples per instance: a KEEP_LAST history deepened and its
/// resource limits widened to match. For a tool that reads every sample (a recorder, an echo)
/// and must not lose the ones it falls a few behind on; KEEP_ALL is left as it is.
eprosima::fastdds::dds::DataReaderQos withDepth(eprosima::fastdds::dds::DataReaderQos qos, std::int32_t depth);

/// A reader of `topic` deepened to `depth` (withDepth of its profile's QoS) and, with
/// `period_ns` > 0, taking at most one sample per that much sim time (withMinimumSeparation),
/// for a subscriber that takes an optional QoS; nothing (the profile's) when both are 0.
std::optional<eprosima::fastdds::dds::DataReaderQos> readerQosWith(Participant& participant, const TopicInfo& topic,
                                                                   std::int32_t depth, std::int64_t period_ns = 0);

}  // namespace quad::dds
