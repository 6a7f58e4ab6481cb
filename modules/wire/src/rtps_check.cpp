// SPDX-License-Identifier: BSD-3-Clause
#include "quad/wire/rtps_check.hpp"

#include <array>
#include <cstring>

#include <fmt/format.h>

namespace quad::wire {

namespace {

// Submessage kinds (DDSI-RTPS 2.5, 9.4.5.1.1) and the security ones (DDS Security 1.1, 7.3.6).
enum : std::uint8_t {
  kPad = 0x01,
  kAckNack = 0x06,
  kHeartbeat = 0x07,
  kGap = 0x08,
  kInfoTs = 0x09,
  kInfoSrc = 0x0c,
  kInfoReplyIp4 = 0x0d,
  kInfoDst = 0x0e,
  kInfoReply = 0x0f,
  kNackFrag = 0x12,
  kHeartbeatFrag = 0x13,
  kData = 0x15,
  kDataFrag = 0x16,
};

constexpr std::size_t kHeaderBytes = 20;
constexpr std::uint32_t kMaxSetBits = 256;  // sequence and fragment number sets
constexpr std::uint16_t kPidPad = 0x0000;
constexpr std::uint16_t kPidSentinel = 0x0001;

std::string kindName(std::uint8_t id)
{
  switch (id) {
    case kPad: return "PAD";
    case kAckNack: return "ACKNACK";
    case kHeartbeat: return "HEARTBEAT";
    case kGap: return "GAP";
    case kInfoTs: return "INFO_TS";
    case kInfoSrc: return "INFO_SRC";
    case kInfoReplyIp4: return "INFO_REPLY_IP4";
    case kInfoDst: return "INFO_DST";
    case kInfoReply: return "INFO_REPLY";
    case kNackFrag: return "NACK_FRAG";
    case kHeartbeatFrag: return "HEARTBEAT_FRAG";
    case kData: return "DATA";
    case kDataFrag: return "DATA_FRAG";
    default: return fmt::format("submessage 0x{:02x}", id);
  }
}

/// The entity id at `at`: big-endian octets whatever the submessage's order.
std::uint32_t entityId(const std::uint8_t* data, std::size_t at)
{
  return std::uint32_t{data[at]} << 24 | std::uint32_t{data[at + 1]} << 16 | std::uint32_t{data[at + 2]} << 8 |
         data[at + 3];
}

/// Reads fields of one endianness from [pos, end) of a datagram; every read checks the end.
class Reader {
public:
  Reader(const std::uint8_t* data, std::size_t pos, std::size_t end, bool little_endian)
      : data_(data), pos_(pos), base_(pos), end_(end), le_(little_endian)
  {
  }

  std::size_t pos() const { return pos_; }
  std::size_t left() const { return end_ - pos_; }

  bool u16(std::uint16_t& v)
  {
    if (left() < 2) {
      return false;
    }
    const std::uint8_t* p = data_ + pos_;
    v = le_ ? static_cast<std::uint16_t>(p[0] | (p[1] << 8)) : static_cast<std::uint16_t>((p[0] << 8) | p[1]);
    pos_ += 2;
    return true;
  }

  bool u32(std::uint32_t& v)
  {
    if (left() < 4) {
      return false;
    }
    const std::uint8_t* p = data_ + pos_;
    v = le_ ? (std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 | std::uint32_t{p[3]} << 24)
            : (std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | std::uint32_t{p[3]});
    pos_ += 4;
    return true;
  }

  /// A sequence number: high (signed) and low words.
  bool sequenceNumber(std::int64_t& v)
  {
    std::uint32_t high = 0;
    std::uint32_t low = 0;
    if (!u32(high) || !u32(low)) {
      return false;
    }
    v = static_cast<std::int64_t>(static_cast<std::int32_t>(high)) * (std::int64_t{1} << 32) + low;
    return true;
  }

  bool skip(std::size_t n)
  {
    if (left() < n) {
      return false;
    }
    pos_ += n;
    return true;
  }

  /// CDR alignment to 4, counted from where this reader began (a 4-aligned offset).
  bool align4()
  {
    const std::size_t pad = (4 - (pos_ - base_) % 4) % 4;
    return skip(std::min(pad, left()));
  }

private:
  const std::uint8_t* data_;
  std::size_t pos_;
  std::size_t base_;
  std::size_t end_;
  bool le_;
};

using Defect = std::optional<RtpsDefect>;

Defect defect(std::size_t offset, std::string what)
{
  return RtpsDefect{offset, std::move(what)};
}

// --- CDR values inside parameters ---------------------------------------------------------

bool cdrString(Reader& r)
{
  std::uint32_t n = 0;
  return r.align4() && r.u32(n) && r.skip(n);
}

bool cdrOctets(Reader& r)
{
  std::uint32_t n = 0;
  return r.align4() && r.u32(n) && r.skip(n);
}

bool cdrStrings(Reader& r)
{
  std::uint32_t count = 0;
  if (!r.align4() || !r.u32(count) || count > r.left() / 4) {  // each at least its length
    return false;
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    if (!cdrString(r)) {
      return false;
    }
  }
  return true;
}

/// seq<Property{string name, string value}>
bool cdrProperties(Reader& r)
{
  std::uint32_t count = 0;
  if (!r.align4() || !r.u32(count) || count > r.left() / 8) {
    return false;
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    if (!cdrString(r) || !cdrString(r)) {
      return false;
    }
  }
  return true;
}

/// seq<BinaryProperty{string name, sequence<octet> value}>
bool cdrBinaryProperties(Reader& r)
{
  std::uint32_t count = 0;
  if (!r.align4() || !r.u32(count) || count > r.left() / 8) {
    return false;
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    if (!cdrString(r) || !cdrOctets(r)) {
      return false;
    }
  }
  return true;
}

/// The value of one parameter, for the parameters whose values Fast DDS decodes into
/// variable-length fields; others are only held to their minimum size.
Defect checkParameterValue(const std::uint8_t* data, std::size_t at, std::uint16_t pid, std::size_t length,
                           bool le)
{
  Reader r(data, at, at + length, le);
  const auto need = [&](std::size_t bytes) -> Defect {
    if (length < bytes) {
      return defect(at - 4, fmt::format("parameter 0x{:04x}: {} bytes, its value needs {}", pid, length, bytes));
    }
    return std::nullopt;
  };
  const auto holds = [&](bool ok, const char* what) -> Defect {
    if (!ok) {
      return defect(at - 4, fmt::format("parameter 0x{:04x}: {} runs past its {} bytes", pid, what, length));
    }
    return std::nullopt;
  };
  switch (pid) {
    case 0x0005:  // PID_TOPIC_NAME
    case 0x0007:  // PID_TYPE_NAME
    case 0x0062:  // PID_ENTITY_NAME
      return holds(cdrString(r), "a string");
    case 0x002c:  // PID_USER_DATA
    case 0x002d:  // PID_GROUP_DATA
    case 0x002e:  // PID_TOPIC_DATA
      return holds(cdrOctets(r), "an octet sequence");
    case 0x0029:  // PID_PARTITION
      return holds(cdrStrings(r), "a string sequence");
    case 0x0073: {  // PID_DATA_REPRESENTATION: sequence<short>
      std::uint32_t count = 0;
      return holds(r.u32(count) && count <= r.left() / 2, "a sequence of representations");
    }
    case 0x0035:  // PID_CONTENT_FILTER_PROPERTY: four strings and the expression's parameters
      return holds(cdrString(r) && cdrString(r) && cdrString(r) && cdrString(r) && cdrStrings(r),
                   "a content filter");
    case 0x0059:  // PID_PROPERTY_LIST: properties, then binary properties if any bytes are left
      return holds(cdrProperties(r) && (r.left() < 4 || cdrBinaryProperties(r)), "a property list");
    case 0x1001:  // PID_IDENTITY_TOKEN
    case 0x1002:  // PID_PERMISSIONS_TOKEN
    case 0x1006:  // PID_IDENTITY_STATUS_TOKEN: DataHolder
      return holds(cdrString(r) && cdrProperties(r) && cdrBinaryProperties(r), "a security token");
    case 0x002f:  // locators: kind, port, 16-byte address
    case 0x0030:
    case 0x0031:
    case 0x0032:
    case 0x0033:
    case 0x0048:
      return need(24);
    case 0x0050:  // GUIDs
    case 0x0052:
    case 0x005a:
    case 0x0070:  // PID_KEY_HASH
      return need(16);
    case 0x0002:  // PID_PARTICIPANT_LEASE_DURATION
    case 0x1004:  // PID_ENDPOINT_SECURITY_INFO
    case 0x1005:  // PID_PARTICIPANT_SECURITY_INFO
      return need(8);
    case 0x0015:  // PID_PROTOCOL_VERSION
    case 0x0016:  // PID_VENDORID
    case 0x0043:  // PID_PARTICIPANT_BUILTIN_ENDPOINTS
    case 0x0058:  // PID_BUILTIN_ENDPOINT_SET
    case 0x0071:  // PID_STATUS_INFO
      return need(4);
    default:
      return std::nullopt;
  }
}

/// A parameter list in [at, end): every parameter inside, ended by PID_SENTINEL. Sets
/// `list_end` past the sentinel.
Defect checkParameterList(const std::uint8_t* data, std::size_t at, std::size_t end, bool le, const char* where,
                          std::size_t& list_end)
{
  Reader r(data, at, end, le);
  for (;;) {
    const std::size_t param = r.pos();
    std::uint16_t pid = 0;
    std::uint16_t length = 0;
    if (!r.u16(pid) || !r.u16(length)) {
      return defect(param, fmt::format("{}: parameter list without a sentinel", where));
    }
    if (pid == kPidSentinel) {
      list_end = r.pos();
      return std::nullopt;
    }
    if (length % 4 != 0) {
      return defect(param, fmt::format("{}: parameter 0x{:04x} has length {}, not a multiple of 4", where, pid, length));
    }
    if (length > r.left()) {
      return defect(param, fmt::format("{}: parameter 0x{:04x} of {} bytes runs {} bytes past its list", where, pid,
                                       length, length - r.left()));
    }
    // Vendor-specific parameters (bit 15) mean what their vendor says: only their length.
    if (pid != kPidPad && (pid & 0x8000) == 0) {
      if (auto d = checkParameterValue(data, r.pos(), static_cast<std::uint16_t>(pid & 0x3fff), length, le)) {
        d->what = std::string(where) + ": " + d->what;
        return d;
      }
    }
    r.skip(length);
  }
}

/// A sequence or fragment number set: base, bit count (at most 256), then its bitmap words.
bool numberSet(Reader& r, bool sequence_numbers, std::uint32_t& bits)
{
  if (!r.skip(sequence_numbers ? 8 : 4) || !r.u32(bits) || bits > kMaxSetBits) {
    return false;
  }
  return r.skip(4 * ((bits + 31) / 32));
}

/// The builtin writers whose DATA payloads are parameter lists Fast DDS decodes: participant
/// (SPDP), publications and subscriptions (SEDP), and their secure versions. The liveliness
/// writer's payload (ParticipantMessageData) is plain CDR, whatever encapsulation it claims.
bool isDiscoveryWriter(std::uint32_t entity)
{
  switch (entity) {
    case 0x000100c2:  // SPDP participant
    case 0x000003c2:  // SEDP publications
    case 0x000004c2:  // SEDP subscriptions
    case 0xff0003c2:  // secure SEDP publications
    case 0xff0004c2:  // secure SEDP subscriptions
    case 0xff0101c2:  // secure SPDP participant
      return true;
    default:
      return false;
  }
}

/// Where the value of parameter `wanted` begins in a list checkParameterList accepted; 0 when
/// the list has none.
std::size_t findParameter(const std::uint8_t* data, std::size_t at, std::size_t end, bool le, std::uint16_t wanted)
{
  Reader r(data, at, end, le);
  std::uint16_t pid = 0;
  std::uint16_t length = 0;
  while (r.u16(pid) && r.u16(length) && pid != kPidSentinel) {
    if (pid == wanted) {
      return r.pos();
    }
    r.skip(length);
  }
  return 0;
}

/// A sample of a keyed user topic whose inline QoS carries its key hash (writers send it to
/// readers that expect inline QoS, as quad's do): the hash must be the key its payload holds.
/// Fast DDS files a sample under the instance its hash names, so a flipped bit in either would
/// invent an instance, and Fast DDS 2.9's instance bookkeeping is not safe against that. The
/// payload's key is quad's: each keyed type leads with Header, whose first member, vehicle_id,
/// is the whole key, hashed as DDS-XTypes says (big-endian, zero-padded to 16 bytes).
Defect checkSampleKey(const std::uint8_t* data, std::size_t qos_at, std::size_t payload, std::size_t end, bool le,
                      std::uint32_t writer, const char* name)
{
  constexpr std::uint16_t kPidKeyHash = 0x0070;
  constexpr std::uint32_t kUserWriterWithKey = 0x02;
  if ((writer & 0xff) != kUserWriterWithKey || end - payload < 8) {
    return std::nullopt;
  }
  const std::size_t hash = findParameter(data, qos_at, payload, le, kPidKeyHash);
  // The encapsulation identifier is big-endian whatever the submessage's order.
  const std::uint16_t encapsulation = static_cast<std::uint16_t>((data[payload] << 8) | data[payload + 1]);
  if (hash == 0 || encapsulation > 0x0001) {  // no hash, or neither CDR_BE nor CDR_LE
    return std::nullopt;
  }
  std::uint32_t vehicle = 0;
  Reader(data, payload + 4, end, encapsulation == 0x0001).u32(vehicle);
  std::array<std::uint8_t, 16> expected{};
  for (int i = 0; i < 4; ++i) {
    expected[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(vehicle >> (24 - 8 * i));
  }
  if (std::memcmp(data + hash, expected.data(), expected.size()) != 0) {
    std::string hex;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      hex += fmt::format("{:02x}", data[hash + i]);
    }
    return defect(hash, fmt::format("{} from writer 0x{:08x}: key hash {} is not the payload's key (vehicle {})", name,
                                    writer, hex, vehicle));
  }
  return std::nullopt;
}

/// DATA and DATA_FRAG after their fixed fields: inline QoS if flagged, then the payload, the
/// part Fast DDS decodes itself (a discovery PL_CDR payload) checked too.
Defect checkDataTail(const std::uint8_t* data, std::size_t body, std::size_t end, std::uint16_t to_inline_qos,
                     std::size_t fixed, bool le, bool has_qos, const char* name, std::size_t& payload_at)
{
  if (to_inline_qos < fixed - 4) {
    return defect(body, fmt::format("{}: octetsToInlineQos {} points inside its own fields", name, to_inline_qos));
  }
  std::size_t at = body + 4 + to_inline_qos;
  if (at > end) {
    return defect(body, fmt::format("{}: octetsToInlineQos {} points {} bytes past the submessage", name, to_inline_qos,
                                    at - end));
  }
  if (has_qos) {
    const std::string where = std::string(name) + " inline QoS";
    if (auto d = checkParameterList(data, at, end, le, where.c_str(), at)) {
      return d;
    }
  }
  payload_at = at;
  return std::nullopt;
}

Defect checkData(const std::uint8_t* data, std::size_t body, std::size_t end, std::uint8_t flags, bool le)
{
  const bool q = (flags & 0x02) != 0;
  const bool d = (flags & 0x04) != 0;
  const bool k = (flags & 0x08) != 0;
  Reader r(data, body, end, le);
  std::uint16_t to_inline_qos = 0;
  std::int64_t sn = 0;
  if (!r.skip(2) || !r.u16(to_inline_qos) || !r.skip(4) || r.left() < 4) {
    return defect(body, fmt::format("DATA: {} bytes, shorter than its 20 bytes of fields", end - body));
  }
  const std::uint32_t writer = entityId(data, r.pos());
  if (!r.skip(4) || !r.sequenceNumber(sn)) {
    return defect(body, fmt::format("DATA: {} bytes, shorter than its 20 bytes of fields", end - body));
  }
  if (sn <= 0) {
    return defect(body, fmt::format("DATA: sequence number {}", sn));
  }
  if (d && k) {
    return defect(body, "DATA: both data and key flags set");
  }
  std::size_t payload = end;
  if (auto defect_found = checkDataTail(data, body, end, to_inline_qos, 20, le, q, "DATA", payload)) {
    return defect_found;
  }
  if (!d && !k) {
    return std::nullopt;
  }
  if (end - payload < 4) {
    return defect(payload, fmt::format("DATA: a payload of {} bytes, without its encapsulation header", end - payload));
  }
  if (!isDiscoveryWriter(writer)) {
    // User data: its key here, the rest by the typed readers against its IDL.
    return q && d ? checkSampleKey(data, body + 4 + to_inline_qos, payload, end, le, writer, "DATA") : std::nullopt;
  }
  // The encapsulation identifier is big-endian whatever the submessage's order.
  const std::uint16_t encapsulation = static_cast<std::uint16_t>((data[payload] << 8) | data[payload + 1]);
  if (encapsulation != 0x0002 && encapsulation != 0x0003) {  // PL_CDR_BE, PL_CDR_LE
    return defect(payload, fmt::format("DATA from discovery writer 0x{:08x}: encapsulation 0x{:04x}, not a "
                                       "parameter list",
                                       writer, encapsulation));
  }
  std::size_t list_end = 0;
  const std::string where = fmt::format("DATA from discovery writer 0x{:08x}", writer);
  return checkParameterList(data, payload + 4, end, encapsulation == 0x0003, where.c_str(), list_end);
}

Defect checkDataFrag(const std::uint8_t* data, std::size_t body, std::size_t end, std::uint8_t flags, bool le)
{
  Reader r(data, body, end, le);
  std::uint16_t to_inline_qos = 0;
  std::int64_t sn = 0;
  std::uint32_t start = 0;
  std::uint16_t count = 0;
  std::uint16_t fragment_size = 0;
  std::uint32_t sample_size = 0;
  if (!r.skip(2) || !r.u16(to_inline_qos) || !r.skip(8) || !r.sequenceNumber(sn) || !r.u32(start) ||
      !r.u16(count) || !r.u16(fragment_size) || !r.u32(sample_size)) {
    return defect(body, fmt::format("DATA_FRAG: {} bytes, shorter than its 32 bytes of fields", end - body));
  }
  if (sn <= 0) {
    return defect(body, fmt::format("DATA_FRAG: sequence number {}", sn));
  }
  if (fragment_size == 0 || sample_size == 0 || start == 0 || count == 0) {
    return defect(body, fmt::format("DATA_FRAG: fragment size {}, sample size {}, first fragment {}, {} fragments: "
                                    "each must be positive",
                                    fragment_size, sample_size, start, count));
  }
  if (sample_size > kMaxSampleBytes) {
    return defect(body, fmt::format("DATA_FRAG: a sample of {} bytes, more than the {} accepted", sample_size,
                                    kMaxSampleBytes));
  }
  const std::uint64_t total = (std::uint64_t{sample_size} + fragment_size - 1) / fragment_size;
  if (std::uint64_t{start} + count - 1 > total) {
    return defect(body, fmt::format("DATA_FRAG: fragments {} to {} of a sample that has {}", start,
                                    std::uint64_t{start} + count - 1, total));
  }
  std::size_t payload = end;
  if (auto d = checkDataTail(data, body, end, to_inline_qos, 32, le, (flags & 0x02) != 0, "DATA_FRAG", payload)) {
    return d;
  }
  // The bytes carried: at most `count` fragments, ending inside the sample (a last fragment's
  // submessage may be padded to 4 bytes).
  const std::uint64_t present = end - payload;
  const std::uint64_t first_byte = std::uint64_t{start - 1} * fragment_size;
  if (present > std::uint64_t{count} * fragment_size + 3 || first_byte + present > std::uint64_t{sample_size} + 3) {
    return defect(body, fmt::format("DATA_FRAG: {} bytes of fragment data from byte {} of a {}-byte sample in "
                                    "{} fragments of {}",
                                    present, first_byte, sample_size, count, fragment_size));
  }
  if (start != 1 || (flags & 0x02) == 0) {
    return std::nullopt;  // the key is in the first fragment's bytes
  }
  return checkSampleKey(data, body + 4 + to_inline_qos, payload, end, le, entityId(data, body + 8), "DATA_FRAG");
}

/// A submessage body in [body, end), given its kind and flags.
Defect checkSubmessage(const std::uint8_t* data, std::size_t body, std::size_t end, std::uint8_t id,
                       std::uint8_t flags)
{
  const bool le = (flags & 0x01) != 0;
  const std::size_t length = end - body;
  const auto atLeast = [&](std::size_t bytes) -> Defect {
    if (length < bytes) {
      return defect(body - 4, fmt::format("{}: {} bytes, shorter than its {} bytes of fields", kindName(id), length,
                                          bytes));
    }
    return std::nullopt;
  };
  Reader r(data, body, end, le);
  switch (id) {
    case kAckNack: {
      std::uint32_t bits = 0;
      if (!r.skip(8) || !numberSet(r, true, bits) || !r.skip(4)) {
        return defect(body - 4, fmt::format("ACKNACK: its sequence number set ({} bits) and count need more than "
                                            "its {} bytes",
                                            bits, length));
      }
      return std::nullopt;
    }
    case kHeartbeat: {
      std::int64_t first = 0;
      std::int64_t last = 0;
      if (!r.skip(8) || !r.sequenceNumber(first) || !r.sequenceNumber(last) || !r.skip(4)) {
        return atLeast(28);
      }
      if (first <= 0 || last < first - 1) {
        return defect(body - 4, fmt::format("HEARTBEAT: first {} and last {} sequence numbers", first, last));
      }
      return std::nullopt;
    }
    case kGap: {
      std::int64_t gap_start = 0;
      std::uint32_t bits = 0;
      if (!r.skip(8) || !r.sequenceNumber(gap_start) || !numberSet(r, true, bits)) {
        return defect(body - 4, fmt::format("GAP: its sequence number set ({} bits) needs more than its {} bytes",
                                            bits, length));
      }
      if (gap_start <= 0) {
        return defect(body - 4, fmt::format("GAP: starts at sequence number {}", gap_start));
      }
      return std::nullopt;
    }
    case kNackFrag: {
      std::int64_t sn = 0;
      std::uint32_t bits = 0;
      if (!r.skip(8) || !r.sequenceNumber(sn) || !numberSet(r, false, bits) || !r.skip(4)) {
        return defect(body - 4, fmt::format("NACK_FRAG: its fragment number set ({} bits) and count need more "
                                            "than its {} bytes",
                                            bits, length));
      }
      return std::nullopt;
    }
    case kHeartbeatFrag:
      return atLeast(24);
    case kInfoTs:
      return (flags & 0x02) != 0 ? std::nullopt : atLeast(8);  // I flag: no timestamp
    case kInfoSrc:
      return atLeast(20);
    case kInfoDst:
      return atLeast(12);
    case kInfoReplyIp4:
      return atLeast((flags & 0x02) != 0 ? 16 : 8);
    case kInfoReply: {
      std::uint32_t count = 0;
      bool ok = r.u32(count) && count <= r.left() / 24 && r.skip(24 * std::size_t{count});
      if (ok && (flags & 0x02) != 0) {  // M flag: multicast locators too
        ok = r.u32(count) && count <= r.left() / 24;
      }
      if (!ok) {
        return defect(body - 4, fmt::format("INFO_REPLY: its locator lists run past its {} bytes", length));
      }
      return std::nullopt;
    }
    case kData:
      return checkData(data, body, end, flags, le);
    case kDataFrag:
      return checkDataFrag(data, body, end, flags, le);
    default:
      // PAD, the security submessages (their content is encrypted) and kinds this parser
      // does not know: Fast DDS skips what it does not know by its length, checked already.
      return std::nullopt;
  }
}

/// The count of a well-formed submessage body in [body, end) that carries one.
std::optional<RtpsCount> countOf(const std::uint8_t* data, std::size_t body, std::size_t end, std::uint8_t id,
                                 bool le)
{
  Reader r(data, body, end, le);
  RtpsCount c;
  std::uint32_t bits = 0;
  bool counted = false;
  switch (id) {
    case kHeartbeat:  // reader, writer, first and last sequence numbers, count
      counted = r.skip(24) && r.u32(c.count);
      break;
    case kHeartbeatFrag:  // reader, writer, sequence number, last fragment, count
      counted = r.skip(20) && r.u32(c.count);
      break;
    case kAckNack:  // reader, writer, sequence number set, count
      counted = r.skip(8) && numberSet(r, true, bits) && r.u32(c.count);
      break;
    case kNackFrag:  // reader, writer, sequence number, fragment number set, count
      counted = r.skip(16) && numberSet(r, false, bits) && r.u32(c.count);
      break;
    default:
      break;
  }
  if (!counted) {
    return std::nullopt;
  }
  c.kind = id;
  c.per_writer = id == kHeartbeat || id == kHeartbeatFrag;
  c.offset = body - 4;
  c.count_offset = r.pos() - 4;
  c.little_endian = le;
  c.reader_id = entityId(data, body);
  c.writer_id = entityId(data, body + 4);
  return c;
}

/// The sequence number a well-formed submessage body in [body, end) states of its writer.
std::optional<RtpsSequence> sequenceOf(const std::uint8_t* data, std::size_t body, std::size_t end, std::uint8_t id,
                                       bool le)
{
  Reader r(data, body, end, le);
  RtpsSequence s;
  switch (id) {
    case kData:
    case kDataFrag:  // extra flags, octetsToInlineQos, reader, writer, sequence number
      if (!r.skip(12) || !r.sequenceNumber(s.last)) {
        return std::nullopt;
      }
      s.writer_id = entityId(data, body + 8);
      break;
    case kHeartbeat:  // reader, writer, first, last
      if (!r.skip(16) || !r.sequenceNumber(s.last)) {
        return std::nullopt;
      }
      s.writer_id = entityId(data, body + 4);
      break;
    case kHeartbeatFrag:  // reader, writer, sequence number
      if (!r.skip(8) || !r.sequenceNumber(s.last)) {
        return std::nullopt;
      }
      s.writer_id = entityId(data, body + 4);
      break;
    case kGap: {  // reader, writer, start, then the list: base, bit count, bitmap
      std::int64_t base = 0;
      std::uint32_t bits = 0;
      if (!r.skip(16) || !r.sequenceNumber(base) || !r.u32(bits)) {
        return std::nullopt;
      }
      s.writer_id = entityId(data, body + 4);
      s.last = base - 1 + bits;
      break;
    }
    default:
      return std::nullopt;
  }
  s.kind = id;
  s.offset = body - 4;
  return s;
}

}  // namespace

std::optional<RtpsDefect> checkRtpsDatagram(const std::uint8_t* data, std::size_t size, std::vector<RtpsCount>* counts,
                                            std::vector<RtpsSequence>* sequences)
{
  if (size < kHeaderBytes) {
    return defect(0, fmt::format("{} bytes, shorter than an RTPS header", size));
  }
  if (std::memcmp(data, "RTPS", 4) != 0) {
    return defect(0, "no RTPS protocol identifier");
  }
  if (data[4] != 2) {
    return defect(4, fmt::format("protocol version {}.{}, not 2.x", data[4], data[5]));
  }
  std::size_t at = kHeaderBytes;
  if (at == size) {
    return defect(at, "an RTPS header without submessages");
  }
  std::array<std::uint8_t, 12> prefix{};  // the sender's, until an INFO_SRC names another
  std::memcpy(prefix.data(), data + 8, prefix.size());
  const std::size_t counts_before = counts != nullptr ? counts->size() : 0;
  const std::size_t sequences_before = sequences != nullptr ? sequences->size() : 0;
  while (at < size) {
    if (size - at < 4) {
      return defect(at, fmt::format("{} bytes left, too few for a submessage header", size - at));
    }
    const std::uint8_t id = data[at];
    const std::uint8_t flags = data[at + 1];
    const bool le = (flags & 0x01) != 0;
    const std::uint16_t length =
        le ? static_cast<std::uint16_t>(data[at + 2] | (data[at + 3] << 8)) : static_cast<std::uint16_t>((data[at + 2] << 8) | data[at + 3]);
    const std::size_t body = at + 4;
    std::size_t end = body + length;
    if (length == 0 && id != kPad && id != kInfoTs) {
      end = size;  // the submessage extends to the end of the datagram
    }
    if (end > size) {
      return defect(at, fmt::format("{}: {} bytes announced, {} left in the datagram", kindName(id), length,
                                    size - body));
    }
    if (auto d = checkSubmessage(data, body, end, id, flags)) {
      if (counts != nullptr) {
        counts->resize(counts_before);  // counts only of a well-formed message
      }
      if (sequences != nullptr) {
        sequences->resize(sequences_before);
      }
      return d;
    }
    if (id == kInfoSrc) {
      std::memcpy(prefix.data(), data + body + 8, prefix.size());
      at = end;
      continue;
    }
    if (counts != nullptr) {
      if (auto c = countOf(data, body, end, id, le)) {
        c->prefix = prefix;
        counts->push_back(*c);
      }
    }
    if (sequences != nullptr) {
      if (auto s = sequenceOf(data, body, end, id, le)) {
        s->prefix = prefix;
        sequences->push_back(*s);
      }
    }
    at = end;
  }
  return std::nullopt;
}

}  // namespace quad::wire
