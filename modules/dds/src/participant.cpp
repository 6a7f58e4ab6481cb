// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/payload_header.hpp"
#include "quad/dds/participant.hpp"

#include <algorithm>
#include <cstdlib>
#include <set>
#include <sstream>
#include <stdexcept>
#include <fstream>
#include <typeinfo>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/topic/ContentFilteredTopic.hpp>
#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <fastrtps/xmlparser/XMLProfileManager.h>
#include <spdlog/spdlog.h>

#include "quad/wire/fault_transport.hpp"
#include "participant_inputs.hpp"
#include "quad/common/identity.hpp"
#include "quad/dds/sim_period_filter.hpp"
#include "quad/dds/topics.hpp"
#include "quad/wire/validating_transport.hpp"

namespace quad::dds {

namespace fdds = eprosima::fastdds::dds;
namespace frtps = eprosima::fastrtps::rtps;

namespace {

constexpr std::uint32_t kUdpReceiveBuffer = 4u << 20;  // the kernel caps it at net.core.rmem_max

/// UDPv4 for quad: with the datagram size `max_message` when it is set, on `interfaces`
/// only when there are any.
std::shared_ptr<eprosima::fastdds::rtps::UDPv4TransportDescriptor> udpDescriptor(
    std::uint32_t max_message, const std::vector<std::string>& interfaces)
{
  auto d = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  // A burst (a map snapshot, a depth cloud, a round's samples) must not overflow the socket
  // while the receiving thread is busy: best-effort samples lost there are lost for good.
  d->receiveBufferSize = kUdpReceiveBuffer;
  if (max_message != 0) {
    d->maxMessageSize = max_message;
  }
  d->interfaceWhiteList = interfaces;
  return d;
}

/// Loads each QoS file once per process (Fast DDS refuses duplicate profile names).
void loadProfiles(const std::filesystem::path& file)
{
  static std::mutex mutex;
  static std::set<std::filesystem::path> loaded;
  std::lock_guard lock(mutex);
  if (loaded.contains(file)) {
    return;
  }
  if (!std::filesystem::exists(file)) {
    throw std::runtime_error("QoS profiles file " + file.string() + " does not exist");
  }
  if (fdds::DomainParticipantFactory::get_instance()->load_XML_profiles_file(file.string()) !=
      ReturnCode_t::RETCODE_OK) {
    throw std::runtime_error("QoS profiles file " + file.string() + " could not be loaded");
  }
  loaded.insert(file);
}

std::string guidText(const frtps::GUID_t& guid)
{
  std::ostringstream os;
  os << guid;
  return os.str();
}

std::string prefixText(const frtps::GuidPrefix_t& prefix)
{
  std::ostringstream os;
  os << prefix;
  return os.str();
}

}  // namespace

void SharedParticipant::enableSecurity(fdds::DomainParticipantQos& qos) const
{
  const std::string identity =
      options_.security_identity.empty() ? common::securityIdentity(options_.name) : options_.security_identity;
  const common::SecurityFiles files = common::securityFiles(options_.security_dir, identity);
  for (const auto& f : {files.ca, files.certificate, files.key, files.governance, files.permissions}) {
    std::ifstream readable(f);
    if (!readable) {
      throw std::invalid_argument("participant '" + options_.name + "': security identity '" + identity +
                                  "': cannot read " + f.string() + " (made by quad security init)");
    }
  }
  const auto file = [](const std::filesystem::path& p) { return "file://" + std::filesystem::absolute(p).string(); };
  auto& properties = qos.properties().properties();
  properties.emplace_back("dds.sec.auth.plugin", "builtin.PKI-DH");
  properties.emplace_back("dds.sec.auth.builtin.PKI-DH.identity_ca", file(files.ca));
  properties.emplace_back("dds.sec.auth.builtin.PKI-DH.identity_certificate", file(files.certificate));
  properties.emplace_back("dds.sec.auth.builtin.PKI-DH.private_key", file(files.key));
  // The 2.9 documentation names another value; this is the one the library registers.
  properties.emplace_back("dds.sec.access.plugin", "builtin.Access-Permissions");
  properties.emplace_back("dds.sec.access.builtin.Access-Permissions.permissions_ca", file(files.ca));
  properties.emplace_back("dds.sec.access.builtin.Access-Permissions.governance", file(files.governance));
  properties.emplace_back("dds.sec.access.builtin.Access-Permissions.permissions", file(files.permissions));
  properties.emplace_back("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

void intraprocessDeliveryOff()
{
  auto settings = eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings();
  settings.intraprocess_delivery = eprosima::fastrtps::INTRAPROCESS_OFF;
  eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings(settings);
}

/// Discovery callbacks: copy what was seen and hand it to the participant.
class SharedParticipant::Listener : public fdds::DomainParticipantListener {
public:
  explicit Listener(SharedParticipant& owner) : owner_(owner) {}

  void on_publisher_discovery(fdds::DomainParticipant*, frtps::WriterDiscoveryInfo&& info) override
  {
    const auto& d = info.info;
    RemoteEndpoint e{guidText(d.guid()), d.topicName().to_string(), d.typeName().to_string(),
                     d.topicKind() == frtps::WITH_KEY, true,
                     d.m_qos.m_reliability.kind == fdds::RELIABLE_RELIABILITY_QOS,
                     d.m_qos.m_durability.kind != fdds::VOLATILE_DURABILITY_QOS};
    owner_.onRemoteEndpoint(std::move(e),
                            info.status != frtps::WriterDiscoveryInfo::REMOVED_WRITER);
  }

  void on_participant_discovery(fdds::DomainParticipant*, frtps::ParticipantDiscoveryInfo&& info) override
  {
    const auto& d = info.info;
    std::string host;
    std::set<std::string> seen;
    for (const auto* list : {&d.default_locators.unicast, &d.metatraffic_locators.unicast}) {
      for (const auto& l : *list) {
        const std::string ip = frtps::IPLocator::ip_to_string(l);
        if (l.kind == LOCATOR_KIND_UDPv4 && seen.insert(ip).second) {
          host += (host.empty() ? "" : ", ") + ip;
        }
      }
    }
    if (host.empty() && !d.default_locators.unicast.empty()) {
      host = "this machine (shared memory)";
    }
    const bool alive = info.status == frtps::ParticipantDiscoveryInfo::DISCOVERED_PARTICIPANT ||
                       info.status == frtps::ParticipantDiscoveryInfo::CHANGED_QOS_PARTICIPANT;
    if (auto* faults = owner_.datagramFaults(); faults != nullptr && alive) {
      wire::DatagramFaults::GuidPrefix prefix;
      std::copy_n(d.m_guid.guidPrefix.value, prefix.size(), prefix.begin());
      faults->learnSender(prefix, d.m_participantName.to_string());
    }
    if (info.status == frtps::ParticipantDiscoveryInfo::DROPPED_PARTICIPANT) {
      // Its lease ran out (killed, stopped, cut off). Where the other side kept this one, the
      // two may never match again once it is heard from (docs/dds.md, "Leases").
      spdlog::warn("DDS: participant {} at {} dropped: not heard from within its lease", d.m_participantName.to_string(),
                   host.empty() ? "an unknown address" : host);
    }
    owner_.onRemoteParticipant(prefixText(d.m_guid.guidPrefix), {d.m_participantName.to_string(), host}, alive);
  }

  void on_subscriber_discovery(fdds::DomainParticipant*, frtps::ReaderDiscoveryInfo&& info) override
  {
    const auto& d = info.info;
    RemoteEndpoint e{guidText(d.guid()), d.topicName().to_string(), d.typeName().to_string(),
                     d.topicKind() == frtps::WITH_KEY, false,
                     d.m_qos.m_reliability.kind == fdds::RELIABLE_RELIABILITY_QOS,
                     d.m_qos.m_durability.kind != fdds::VOLATILE_DURABILITY_QOS};
    owner_.onRemoteEndpoint(std::move(e),
                            info.status != frtps::ReaderDiscoveryInfo::REMOVED_READER);
  }

private:
  SharedParticipant& owner_;
};

SharedParticipant::SharedParticipant(ParticipantOptions options)
    : options_(std::move(options)), listener_(std::make_unique<Listener>(*this))
{
  if (options_.domain_id < 0 || options_.domain_id > kMaxDomainId) {
    throw std::invalid_argument("domain id: " + std::to_string(options_.domain_id) +
                                ": expected an integer in [0, " + std::to_string(kMaxDomainId) + "]");
  }
  if (options_.qos_file.empty()) {
    options_.qos_file = defaultQosFile();
  }
  // A DEFAULT_FASTRTPS_PROFILES.xml in the working directory must not change quad's QoS.
  setenv("SKIP_DEFAULT_XML_FILE", "1", 1);
  loadProfiles(options_.qos_file);

  auto* factory = fdds::DomainParticipantFactory::get_instance();
  fdds::DomainParticipantQos qos;
  if (factory->get_participant_qos_from_profile("quad.participant", qos) != ReturnCode_t::RETCODE_OK) {
    throw std::runtime_error("QoS profiles file " + options_.qos_file.string() +
                             " has no participant profile 'quad.participant'");
  }
  qos.name(options_.name);

  using TransportDescriptor = std::shared_ptr<eprosima::fastdds::rtps::TransportDescriptorInterface>;
  const auto checked = [this](TransportDescriptor udp) {
    return options_.validate_datagrams ? wire::validatingTransport(std::move(udp)) : udp;
  };
  if (options_.udp_max_message != 0 && options_.transport != Transport::kUdp && !options_.fault_layer) {
    throw std::invalid_argument("participant '" + options_.name + "': a UDP datagram size of " +
                                std::to_string(options_.udp_max_message) + " bytes needs the udp transport");
  }
  if (!options_.interfaces.empty() && options_.transport == Transport::kSharedMemory) {
    throw std::invalid_argument("participant '" + options_.name + "': interfaces to use (" +
                                options_.interfaces.front() + ", ...) need UDP, and the transport is shared memory");
  }
  if (options_.fault_layer) {
    if (options_.transport == Transport::kSharedMemory) {
      throw std::invalid_argument("participant '" + options_.name +
                                  "': a fault layer needs UDP, and the transport is shared memory");
    }
    options_.transport = Transport::kUdp;  // data-sharing off too (profileQos)
    // Endpoints of one process would otherwise talk through memory, around any transport.
    intraprocessDeliveryOff();
    datagram_faults_ = std::make_shared<wire::DatagramFaults>();
    qos.transport().use_builtin_transports = false;
    qos.transport().user_transports.push_back(
        checked(wire::faultyUdpTransport(datagram_faults_, udpDescriptor(options_.udp_max_message, options_.interfaces))));
  } else {
    switch (options_.transport) {
      case Transport::kDefault:
        if (options_.validate_datagrams || !options_.interfaces.empty()) {
          // Fast DDS's builtin pair, with the UDP one behind the check.
          qos.transport().use_builtin_transports = false;
          qos.transport().user_transports.push_back(
              std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>());
          qos.transport().user_transports.push_back(checked(udpDescriptor(0, options_.interfaces)));
        }
        break;
      case Transport::kUdp:
        qos.transport().use_builtin_transports = false;
        qos.transport().user_transports.push_back(checked(udpDescriptor(options_.udp_max_message, options_.interfaces)));
        break;
      case Transport::kSharedMemory:
        qos.transport().use_builtin_transports = false;
        qos.transport().user_transports.push_back(
            std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>());
        break;
    }
  }

  if (!options_.security_dir.empty()) {
    enableSecurity(qos);
  }

  auto& builtin = qos.wire_protocol().builtin;
  if (options_.participant_lease_s > 0) {
    builtin.discovery_config.leaseDuration = eprosima::fastrtps::Duration_t(options_.participant_lease_s, 0);
  }
  for (const auto& peer : options_.initial_peers) {
    builtin.initialPeersList.push_back(parseLocator(peer, "initial peer", false));
  }
  if (!options_.discovery_server.empty()) {
    frtps::RemoteServerAttributes server;
    frtps::get_server_client_default_guidPrefix(0, server.guidPrefix);
    server.metatrafficUnicastLocatorList.push_back(
        parseLocator(options_.discovery_server, "discovery server", true));
    builtin.discovery_config.discoveryProtocol =
        options_.observe_all ? frtps::DiscoveryProtocol_t::SUPER_CLIENT : frtps::DiscoveryProtocol_t::CLIENT;
    builtin.discovery_config.m_DiscoveryServers.push_back(server);
  }

  participant_ = factory->create_participant(static_cast<fdds::DomainId_t>(options_.domain_id), qos, listener_.get(),
                                             fdds::StatusMask::none());
  if (participant_ == nullptr) {
    throw std::runtime_error(
        "cannot create DDS participant '" + options_.name + "' on domain " + std::to_string(options_.domain_id) +
        (options_.security_dir.empty()
             ? std::string()
             : " (security: its certificate, permissions or governance in " + options_.security_dir.string() +
                   " was refused: expired, not signed by ca.pem, or not for this domain; see the log above)"));
  }
  if (participant_->register_content_filter_factory(kSimPeriodFilterClass, &simPeriodFilterFactory()) !=
      ReturnCode_t::RETCODE_OK) {
    factory->delete_participant(participant_);
    throw std::runtime_error("cannot register the sim-time period filter on participant '" + options_.name + "'");
  }
  own_publisher_ = publisher();
  own_subscriber_ = subscriber();
  if (own_publisher_ == nullptr || own_subscriber_ == nullptr) {
    participant_->delete_contained_entities();
    factory->delete_participant(participant_);
    throw std::runtime_error("cannot create publisher/subscriber of participant '" +
                             options_.name + "'");
  }
}

std::vector<std::string> vehiclePartitions(std::uint32_t vehicle_id)
{
  if (vehicle_id == 0) {
    return {"", "*"};
  }
  return {"vehicle." + std::to_string(vehicle_id)};
}

fdds::Publisher* SharedParticipant::publisher(std::optional<std::uint32_t> vehicle)
{
  const std::uint32_t id = vehicle.value_or(options_.vehicle_id);
  const std::lock_guard lock(partitions_mutex_);
  auto& made = publishers_[id];
  if (made == nullptr) {
    fdds::PublisherQos qos = fdds::PUBLISHER_QOS_DEFAULT;
    for (const std::string& name : vehiclePartitions(id)) {
      qos.partition().push_back(name.c_str());
    }
    made = participant_->create_publisher(qos);
  }
  return made;
}

fdds::Subscriber* SharedParticipant::subscriber(std::optional<std::uint32_t> vehicle)
{
  const std::uint32_t id = vehicle.value_or(options_.vehicle_id);
  const std::lock_guard lock(partitions_mutex_);
  auto& made = subscribers_[id];
  if (made == nullptr) {
    fdds::SubscriberQos qos = fdds::SUBSCRIBER_QOS_DEFAULT;
    for (const std::string& name : vehiclePartitions(id)) {
      qos.partition().push_back(name.c_str());
    }
    made = participant_->create_subscriber(qos);
  }
  return made;
}

SharedParticipant::~SharedParticipant() { close(); }

void SharedParticipant::close()
{
  if (participant_ == nullptr) {
    return;
  }
  // Readers and writers are deleted by their owners first, unless the process ends without
  // destroying them; this removes the rest.
  participant_->set_listener(nullptr);
  participant_->delete_contained_entities();
  fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
  participant_ = nullptr;
}

fdds::Topic* SharedParticipant::topic(const TopicInfo& info, const fdds::TypeSupport& type)
{
  std::lock_guard lock(endpoints_mutex_);
  const fdds::TypeSupport known = participant_->find_type(type.get_type_name());
  // One name, two serialisations (a typed endpoint's and a raw one's) would make Fast DDS
  // serialise one kind of sample with the other's code.
  if (!known.empty() && typeid(*known.get()) != typeid(*type.get())) {
    throw std::logic_error("type " + type.get_type_name() + " of " + std::string(info.name) +
                           " is registered on this participant with another type support (typed and raw "
                           "endpoints of one type need participants of their own)");
  }
  if (auto it = topics_.find(info.name); it != topics_.end()) {
    if (it->second->get_type_name() != type.get_type_name()) {
      throw std::logic_error("topic " + std::string(info.name) + " already created with type " +
                             it->second->get_type_name() + ", not " + type.get_type_name());
    }
    return it->second;
  }
  if (known.empty()) {
    fdds::TypeSupport copy = type;
    if (copy.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
      throw std::runtime_error("cannot register type " + type.get_type_name());
    }
  }
  auto* topic = participant_->create_topic(std::string(info.name), type.get_type_name(),
                                           fdds::TOPIC_QOS_DEFAULT);
  if (topic == nullptr) {
    throw std::runtime_error("cannot create topic " + std::string(info.name));
  }
  topics_.emplace(std::string(info.name), topic);
  return topic;
}

fdds::TopicDescription* SharedParticipant::readerTopic(const TopicInfo& info, const fdds::TypeSupport& type,
                                                 std::int64_t period_ns)
{
  fdds::Topic* plain = topic(info, type);
  if (period_ns <= 0) {
    return plain;
  }
  std::lock_guard lock(endpoints_mutex_);
  // A topic of its own for each such reader: the filter remembers what it passed.
  const std::string name = std::string(info.name) + "|sim_period_" + std::to_string(++filtered_topics_);
  auto* filtered = participant_->create_contentfilteredtopic(name, plain, kSimPeriodFilterExpression,
                                                             {std::to_string(period_ns)}, kSimPeriodFilterClass);
  if (filtered == nullptr) {
    throw std::runtime_error("cannot filter " + std::string(info.name) + " to one sample per " +
                             std::to_string(period_ns) + " ns of sim time");
  }
  return filtered;
}

void SharedParticipant::releaseReaderTopic(fdds::TopicDescription* topic)
{
  if (auto* filtered = dynamic_cast<fdds::ContentFilteredTopic*>(topic)) {
    std::lock_guard lock(endpoints_mutex_);
    participant_->delete_contentfilteredtopic(filtered);
  }
}

void SharedParticipant::addLocalEndpoint(const std::string& topic, const std::string& type_name, bool keyed,
                                         bool writer, std::shared_ptr<EventQueue> events)
{
  std::vector<RemoteEndpoint> remotes;
  {
    std::lock_guard lock(endpoints_mutex_);
    auto& local = local_.try_emplace(topic, LocalEndpoint{type_name, keyed}).first->second;
    local.users.push_back({std::move(events), writer});
    for (const auto& [guid, remote] : remote_) {
      if (remote.topic == topic) {
        remotes.push_back(remote);
      }
    }
  }
  for (const auto& remote : remotes) {
    checkTypes(remote);
  }
}

void SharedParticipant::removeLocalEndpoint(const std::string& topic, bool writer, const EventQueue* events)
{
  std::lock_guard lock(endpoints_mutex_);
  auto it = local_.find(topic);
  if (it == local_.end()) {
    return;
  }
  auto& users = it->second.users;
  const auto user = std::find_if(users.begin(), users.end(), [&](const LocalEndpoint::User& u) {
    return u.events.get() == events && u.writer == writer;
  });
  if (user != users.end()) {
    users.erase(user);
  }
  if (users.empty()) {
    local_.erase(it);
  }
}

std::vector<RemoteEndpoint> SharedParticipant::remoteEndpoints() const
{
  std::lock_guard lock(endpoints_mutex_);
  std::vector<RemoteEndpoint> out;
  out.reserve(remote_.size());
  for (const auto& [guid, endpoint] : remote_) {
    out.push_back(endpoint);
    // A GUID is "<prefix>|<entity>": the prefix names the participant.
    if (const auto p = participants_.find(guid.substr(0, guid.find('|'))); p != participants_.end()) {
      out.back().participant = p->second.name;
      out.back().host = p->second.host;
    }
  }
  return out;
}

void SharedParticipant::onRemoteParticipant(const std::string& prefix, RemoteParticipant participant, bool alive)
{
  std::lock_guard lock(endpoints_mutex_);
  if (alive) {
    participants_[prefix] = std::move(participant);
  } else {
    participants_.erase(prefix);
  }
}

void SharedParticipant::onRemoteEndpoint(RemoteEndpoint endpoint, bool alive)
{
  {
    std::lock_guard lock(endpoints_mutex_);
    if (!alive) {
      remote_.erase(endpoint.guid);
      return;
    }
    remote_[endpoint.guid] = endpoint;
  }
  checkTypes(endpoint);
}

void SharedParticipant::checkTypes(const RemoteEndpoint& remote)
{
  std::string problem;
  std::vector<std::shared_ptr<EventQueue>> told;  // the queues of the nodes whose endpoints it concerns, once each
  {
    std::lock_guard lock(endpoints_mutex_);
    const auto it = local_.find(remote.topic);
    if (it == local_.end()) {
      return;
    }
    const LocalEndpoint& local = it->second;
    // A remote writer concerns our readers, a remote reader our writers.
    for (const auto& user : local.users) {
      if (user.writer != remote.writer && std::find(told.begin(), told.end(), user.events) == told.end()) {
        told.push_back(user.events);
      }
    }
    if (told.empty()) {
      return;
    }
    const auto kind = [](bool keyed) { return keyed ? "keyed" : "unkeyed"; };
    if (remote.type_name != local.type_name || remote.keyed != local.keyed) {
      problem = std::string("remote ") + (remote.writer ? "writer" : "reader") + " " +
                remote.guid + " has type '" + remote.type_name + "' (" + kind(remote.keyed) +
                "), local " + (remote.writer ? "reader" : "writer") + " has '" + local.type_name +
                "' (" + kind(local.keyed) + "): they will never match";
    }
  }
  if (!problem.empty()) {
    for (const auto& events : told) {
      events->push({EventKind::kTypeMismatch, remote.topic, problem});
    }
  }
}

Participant::Participant(ParticipantOptions options)
    : shared_(std::make_shared<SharedParticipant>(std::move(options))),
      events_(std::make_shared<EventQueue>()),
      reports_process_inputs_(true)
{
}

Participant::Participant(std::shared_ptr<SharedParticipant> shared)
    : shared_(std::move(shared)), events_(std::make_shared<EventQueue>())
{
  if (!shared_) {
    throw std::invalid_argument("a node's participant needs a DDS participant to share; got none");
  }
}

}  // namespace quad::dds
