// SPDX-License-Identifier: BSD-3-Clause
// quad_datagram_fuzzer: sends structure-aware hostile RTPS datagrams (datagram_mutator.hpp)
// to the participants of a domain on a host, to see that none of them ends.
//
//   quad_datagram_fuzzer --domain D [--host IP] [--count N] [--rate R] [--seed S] [--participants P]
//
// Targets the unicast metatraffic and user ports of participant ids 0..P-1 on the host
// (127.0.0.1 unless --host names another; RTPS port mapping: 7400 + 250 * D + 10 / 11 +
// 2 * id) and the domain's discovery multicast port on 239.255.0.1, in turn. R datagrams a
// second (0: as fast as it can).
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "datagram_mutator.hpp"

int main(int argc, char** argv)
{
  long domain = -1;
  unsigned long long count = 1'000'000;
  double rate = 0.0;
  unsigned long long seed = 1;
  long participants = 8;
  in_addr host{htonl(INADDR_LOOPBACK)};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const char* v = argv[i + 1];
    if (a == "--domain") {
      domain = std::strtol(v, nullptr, 10);
    } else if (a == "--count") {
      count = std::strtoull(v, nullptr, 10);
    } else if (a == "--rate") {
      rate = std::strtod(v, nullptr);
    } else if (a == "--seed") {
      seed = std::strtoull(v, nullptr, 10);
    } else if (a == "--host") {
      if (inet_pton(AF_INET, v, &host) != 1) {
        std::fprintf(stderr, "quad_datagram_fuzzer: --host %s: not an IPv4 address\n", v);
        return 2;
      }
    } else if (a == "--participants") {
      participants = std::strtol(v, nullptr, 10);
    } else {
      std::fprintf(stderr, "quad_datagram_fuzzer: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (domain < 0 || domain > 232 || participants < 1 || participants > 100) {
    std::fprintf(stderr, "usage: quad_datagram_fuzzer --domain 0..232 [--host IP] [--count N] [--rate R] [--seed S] "
                         "[--participants 1..100]\n");
    return 2;
  }
  std::vector<sockaddr_in> targets;
  const auto add = [&](std::uint32_t address, long port) {
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(static_cast<std::uint16_t>(port));
    to.sin_addr.s_addr = htonl(address);
    targets.push_back(to);
  };
  const long base = 7400 + 250 * domain;
  for (long id = 0; id < participants; ++id) {
    add(ntohl(host.s_addr), base + 10 + 2 * id);
    add(ntohl(host.s_addr), base + 11 + 2 * id);
  }
  add(0xefff0001, base);  // 239.255.0.1: discovery
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) {
    std::perror("quad_datagram_fuzzer: socket");
    return 1;
  }
  quad::fuzz::DatagramMutator mutator(seed);
  const auto start = std::chrono::steady_clock::now();
  unsigned long long sent = 0;
  for (unsigned long long i = 0; i < count; ++i) {
    const auto d = mutator.next();
    const sockaddr_in& to = targets[i % targets.size()];
    if (::sendto(fd, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof(to)) >= 0) {
      ++sent;
    }
    if (rate > 0.0) {
      std::this_thread::sleep_until(start + std::chrono::duration<double>(static_cast<double>(i + 1) / rate));
    }
  }
  ::close(fd);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("quad_datagram_fuzzer: %llu of %llu datagrams sent to %zu ports in %.1f s (seed %llu)\n", sent, count,
              targets.size(), took, seed);
  return 0;
}
