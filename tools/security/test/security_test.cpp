// SPDX-License-Identifier: BSD-3-Clause
// DDS Security with the files of `quad security init`, between real participants: the
// authorised talk; a participant without a certificate, with one from another authority
// under the same name, or with an expired one, and a module writing a topic it was not
// granted each get no match and no sample, while the authorised keep talking; a container's
// one identity writes what each of its modules may and nothing more; a capture of the
// traffic holds no plaintext payload.
#include <arpa/inet.h>
#include <linux/if_ether.h>
#include <linux/if_packet.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include <thread>

#include "quad/common/identity.hpp"
#include "quad/common/time.hpp"
#include "wait.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/common/identity.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "scratch.hpp"
#include "quad/security/init.hpp"
#include "quad/security/roles.hpp"

namespace quad::security {
namespace {

// ctest runs each case alone and in parallel with others: each has a domain of its own.
constexpr int kTalkDomain = 173;
constexpr int kNoCertificateDomain = 174;
constexpr int kOtherAuthorityDomain = 175;
constexpr int kExpiredDomain = 176;
constexpr int kNotGrantedDomain = 177;
constexpr int kCaptureDomain = 178;
constexpr int kCaptureControlDomain = 179;
constexpr int kContainerDomain = 164;
constexpr double kQuietSeconds = 3.0;  // how long the unauthorised are watched
// A secure match on a busy machine has taken over 10 s (a handshake message resent): the tests
// are about who gets what, not how soon.
constexpr std::chrono::seconds kSecureMatch{30};

namespace fs = std::filesystem;

class Security : public ::testing::Test {
protected:
  void SetUp() override
  {
    dds::intraprocessDeliveryOff();  // several participants in this process
    dir_ = test::scratchDir("quad_security");
    init({dir_ / "domain", 1, false}, quadRoles());
  }

  dds::ParticipantOptions options(const std::string& name, int domain, const fs::path& dir) const
  {
    return dds::ParticipantOptions{.name = name, .domain_id = domain, .transport = dds::Transport::kUdp,
                                   .security_dir = dir};
  }

  fs::path domainDir() const { return dir_ / "domain"; }

  /// The plant writes states to control; `intruder` (if any) listens on the same domain. The
  /// intruder's reader must match nothing and take nothing while control takes the states.
  void expectShutOut(int domain, dds::Participant* intruder)
  {
    dds::Participant plant(options("plant", domain, domainDir()));
    dds::Participant control(options("control", domain, domainDir()));
    dds::Publisher<msg::VehicleState> states(plant, dds::topics::kSimState);
    dds::Subscriber<msg::VehicleState> authorised(control, dds::topics::kSimState);
    std::optional<dds::Subscriber<msg::VehicleState>> unauthorised;
    if (intruder != nullptr) {
      unauthorised.emplace(*intruder, dds::topics::kSimState);
    }
    ASSERT_TRUE(test::waitFor([&] { return authorised.matchedWriters() == 1; }, kSecureMatch));
    int taken = 0;
    int stolen = 0;
    const std::int64_t end = common::steadyTimeNs() + common::toNanoseconds(kQuietSeconds);
    int written = 0;
    while (common::steadyTimeNs() < end) {
      msg::VehicleState s;
      s.header().seq(static_cast<std::uint32_t>(++written));
      states.write(s);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      taken += static_cast<int>(authorised.takeAll().size());
      if (unauthorised) {
        stolen += static_cast<int>(unauthorised->takeAll().size());
        EXPECT_EQ(unauthorised->matchedWriters(), 0);
      }
    }
    EXPECT_GT(taken, written / 2) << "the authorised stopped talking";
    EXPECT_EQ(stolen, 0);
    EXPECT_EQ(states.matchedReaders(), 1);  // control's only
  }

  fs::path dir_;
};

TEST_F(Security, InitWritesPrivateKeysAndSignedDocuments)
{
  const auto files = common::securityFiles(domainDir(), "plant");
  for (const auto& f : {files.ca, files.certificate, files.key, files.governance, files.permissions}) {
    EXPECT_TRUE(fs::exists(f)) << f;
  }
  EXPECT_EQ(fs::status(domainDir()).permissions() & fs::perms::all, fs::perms::owner_all);
  EXPECT_EQ(fs::status(files.key).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
  const std::string permissions = test::readFile(domainDir() / "plant.permissions.xml");
  EXPECT_NE(permissions.find("<subject_name>CN=plant,O=quad</subject_name>"), std::string::npos);
  EXPECT_NE(permissions.find("<topic>quad/sim/state</topic>"), std::string::npos);
  EXPECT_EQ(permissions.find("<topic>quad/control/actuators</topic>"), std::string::npos);
  // The recorder only reads, but for the lockstep reports of its start gate.
  const std::string record = test::readFile(domainDir() / "record.permissions.xml");
  const auto from = record.find("<publish>");
  ASSERT_NE(from, std::string::npos);
  const std::string published = record.substr(from, record.find("</publish>") - from);
  EXPECT_NE(published.find("<topic>quad/sim/lockstep</topic>"), std::string::npos) << published;
  EXPECT_EQ(published.find("<topic>", published.find("<topic>") + 1), std::string::npos) << published;
}

TEST_F(Security, TheBridgeMayPublishOnlyTheOperatorsTopics)
{
  EXPECT_EQ(common::securityIdentity("quad_bridge"), "bridge");
  const std::string permissions = test::readFile(domainDir() / "bridge.permissions.xml");
  const auto from = permissions.find("<publish>");
  const auto to = permissions.find("</publish>");
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  const std::string publish = permissions.substr(from, to - from);
  for (const auto& t : dds::topics::kAll) {
    const bool granted = publish.find("<topic>" + std::string(t.name) + "</topic>") != std::string::npos;
    EXPECT_EQ(granted, t.owner == dds::Owner::kOperator) << t.name;
  }
  EXPECT_NE(permissions.find("<subscribe>"), std::string::npos);
}

TEST_F(Security, AuthorisedModulesTalk)
{
  dds::Participant plant(options("plant", kTalkDomain, domainDir()));
  dds::Participant control(options("control", kTalkDomain, domainDir()));
  dds::Publisher<msg::VehicleState> states(plant, dds::topics::kSimState);
  dds::Subscriber<msg::VehicleState> reader(control, dds::topics::kSimState);
  dds::Publisher<msg::ActuatorCommand> commands(control, dds::topics::kActuators);
  dds::Subscriber<msg::ActuatorCommand> command_reader(plant, dds::topics::kActuators);
  ASSERT_TRUE(test::waitFor([&] { return reader.matchedWriters() == 1 && command_reader.matchedWriters() == 1; },
                              kSecureMatch));
  int got = 0;
  EXPECT_TRUE(test::waitFor([&] {
    states.write(msg::VehicleState{});
    commands.write(msg::ActuatorCommand{});
    got += static_cast<int>(reader.takeAll().size() + command_reader.takeAll().size());
    return got >= 20;
  }));
}

TEST_F(Security, AParticipantWithoutACertificateGetsNothing)
{
  dds::Participant intruder(options("control", kNoCertificateDomain, {}));
  expectShutOut(kNoCertificateDomain, &intruder);
}

TEST_F(Security, ACertificateFromAnotherAuthorityWithTheSameNameGetsNothing)
{
  init({dir_ / "other", 1, false}, quadRoles());
  dds::Participant intruder(options("control", kOtherAuthorityDomain, dir_ / "other"));
  expectShutOut(kOtherAuthorityDomain, &intruder);
}

TEST_F(Security, AnExpiredCertificateGetsNothing)
{
  // The domain's own authority, the right name, the right permissions: only expired.
  const fs::path expired = dir_ / "expired";
  fs::copy(domainDir(), expired);
  const auto ca = security::KeyPair::load(domainDir() / "ca.pem", domainDir() / "ca.key");
  const auto now = security::Clock::now();
  const auto files = common::securityFiles(expired, "control");
  security::KeyPair::makeIdentity(ca, "control", now - std::chrono::hours(48), now - std::chrono::hours(24))
      .save(files.certificate, files.key);
  // Fast DDS refuses to create a participant with it at all: it never reaches the wire.
  EXPECT_THROW(dds::Participant(options("control", kExpiredDomain, expired)), std::exception);
  expectShutOut(kExpiredDomain, nullptr);
}

TEST_F(Security, AModuleCannotWriteATopicItWasNotGranted)
{
  dds::Participant plant(options("plant", kNotGrantedDomain, domainDir()));
  dds::Participant control(options("control", kNotGrantedDomain, domainDir()));
  dds::Subscriber<msg::VehicleState> reader(control, dds::topics::kSimState);
  // Only the plant may write the sim state: control's writer is refused where it is made.
  EXPECT_THROW(dds::Publisher<msg::VehicleState>(control, dds::topics::kSimState), std::exception);
  // And a granted writer still reaches it.
  dds::Publisher<msg::VehicleState> states(plant, dds::topics::kSimState);
  EXPECT_TRUE(test::waitFor([&] { return reader.matchedWriters() == 1; }, kSecureMatch));
}

TEST_F(Security, AContainersIdentityWritesWhatEachOfItsModulesMayAndNothingElse)
{
  const std::vector<std::string> hosted{"plant", "estimation", "control"};
  auto roles = quadRoles();
  roles.push_back(containerRole(hosted));
  const fs::path dir = dir_ / "containers";
  init({dir, 1, false}, roles);
  // One participant for the three, as quad_container makes it: its name is its identity.
  dds::Participant fast(options(common::containerName(hosted), kContainerDomain, dir));
  dds::Participant mapping(options("mapping", kContainerDomain, dir));
  dds::Publisher<msg::VehicleState> states(fast, dds::topics::kSimState);           // the plant's
  dds::Publisher<msg::EstimatedState> estimates(fast, dds::topics::kEstimatedState);  // estimation's
  dds::Publisher<msg::ActuatorCommand> commands(fast, dds::topics::kActuators);       // control's
  // The planner's path is none of theirs: refused where it is made.
  EXPECT_THROW(dds::Publisher<msg::Path>(fast, dds::topics::kPath), std::exception);
  dds::Subscriber<msg::EstimatedState> reader(mapping, dds::topics::kEstimatedState);
  ASSERT_TRUE(test::waitFor([&] { return reader.matchedWriters() == 1; }, kSecureMatch));
  int got = 0;
  EXPECT_TRUE(test::waitFor([&] {
    estimates.write(msg::EstimatedState{});
    got += static_cast<int>(reader.takeAll().size());
    return got >= 10;
  }));
}

TEST_F(Security, AContainersRoleNamesOnlyModulesEachOnce)
{
  const Role role = containerRole({"mapping", "planning"});
  EXPECT_EQ(role.identity, "mapping+planning");
  const auto grants = [&](std::string_view topic) {
    return std::find(role.publish.begin(), role.publish.end(), topic) != role.publish.end();
  };
  EXPECT_TRUE(grants(dds::topics::kMapUpdate.info.name));
  EXPECT_TRUE(grants(dds::topics::kPath.info.name));
  EXPECT_FALSE(grants(dds::topics::kActuators.info.name));
  EXPECT_EQ(std::count(role.publish.begin(), role.publish.end(), std::string(dds::topics::kHeartbeat.info.name)), 1);
  EXPECT_THROW(containerRole({"mapping", "record"}), std::invalid_argument);
  EXPECT_THROW(containerRole({"mapping", "mapping"}), std::invalid_argument);
  EXPECT_THROW(containerRole({}), std::invalid_argument);
}

/// Every frame on every interface of this host while it lives (an AF_PACKET socket: root).
class Capture {
public:
  Capture()
  {
    fd_ = ::socket(AF_PACKET, SOCK_RAW, htons(ETH_P_ALL));
    if (fd_ < 0) {
      return;
    }
    timeval timeout{0, 100'000};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
    thread_ = std::thread([this] {
      std::vector<char> frame(65536);
      while (!stop_) {
        const ssize_t n = ::recv(fd_, frame.data(), frame.size(), 0);
        if (n > 0) {
          bytes_.append(frame.data(), static_cast<std::size_t>(n));
        }
      }
    });
  }
  ~Capture() { stopped(); }
  bool open() const { return fd_ >= 0; }

  /// Stops capturing; what was captured.
  const std::string& stopped()
  {
    if (thread_.joinable()) {
      stop_ = true;
      thread_.join();
      ::close(fd_);
    }
    return bytes_;
  }

private:
  int fd_ = -1;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  std::string bytes_;
};

/// Sends 50 events whose detail is `marker` from the plant to control on `domain` (security
/// from `dir`, or off when empty) while capturing; returns how many arrived and the capture.
std::pair<int, std::string> sendCaptured(int domain, const fs::path& dir, const std::string& marker)
{
  const auto options = [&](const char* name) {
    return dds::ParticipantOptions{
        .name = name, .domain_id = domain, .transport = dds::Transport::kUdp, .security_dir = dir};
  };
  Capture capture;
  EXPECT_TRUE(capture.open()) << "capturing needs root";
  dds::Participant plant(options("plant"));
  dds::Participant control(options("control"));
  dds::Publisher<msg::SimEvent> events(plant, dds::topics::kSimEvents);
  dds::Subscriber<msg::SimEvent> reader(control, dds::topics::kSimEvents);
  EXPECT_TRUE(test::waitFor([&] { return reader.matchedWriters() == 1; }, kSecureMatch));
  int got = 0;
  for (int i = 0; i < 50; ++i) {
    msg::SimEvent e;
    e.detail(marker);
    events.write(e);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    got += static_cast<int>(reader.takeAll().size());
  }
  test::waitFor([&] {
    got += static_cast<int>(reader.takeAll().size());
    return got >= 50;
  });
  return {got, capture.stopped()};
}

TEST_F(Security, ACaptureOfTheTrafficHoldsNoPlaintextPayload)
{
  if (::geteuid() != 0) {
    GTEST_SKIP() << "capturing packets needs root";
  }
  const std::string marker = "quad-capture-marker-7f3a9c51e2d84b06";
  // Without security the marker is on the wire: the capture sees what it must not see later.
  const auto [plain_got, plain] = sendCaptured(kCaptureControlDomain, {}, marker);
  EXPECT_EQ(plain_got, 50);
  EXPECT_NE(plain.find(marker), std::string::npos) << "the capture missed the plain traffic";
  const auto [secure_got, secure] = sendCaptured(kCaptureDomain, domainDir(), marker);
  EXPECT_EQ(secure_got, 50);
  EXPECT_GT(secure.size(), 50u * marker.size());  // the encrypted samples were captured...
  EXPECT_EQ(secure.find(marker), std::string::npos) << "plaintext payload on the wire";  // ...unreadable
  EXPECT_EQ(secure.find(marker.substr(0, 16)), std::string::npos);
}

}  // namespace
}  // namespace quad::security
