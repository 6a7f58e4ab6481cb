// Fuzz target: the RTPS structure check every received UDP datagram passes. Whatever the
// bytes, it reads inside them and returns a verdict. Corpus: tests/fixtures/datagrams.
#include "harness.hpp"
#include "quad/dds/rtps_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  // The datagram in a buffer of exactly its size, so that a read past it is caught.
  std::vector<std::uint8_t> datagram(data, data + size);
  (void)quad::dds::checkRtpsDatagram(datagram.data(), datagram.size());
  return 0;
}

std::vector<std::string> quad::fuzz::seeds() { return {}; }
