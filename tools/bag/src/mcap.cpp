// SPDX-License-Identifier: BSD-3-Clause
#include "quad/bag/mcap.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>

#include <zstd.h>

namespace quad::bag {

namespace {

constexpr char kMagic[] = "\x89MCAP0\r\n";  // 8 bytes
constexpr std::size_t kMagicSize = 8;

enum Op : std::uint8_t {
  kHeader = 0x01, kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05, kChunk = 0x06,
  kMessageIndex = 0x07, kChunkIndex = 0x08, kStatistics = 0x0B, kMetadata = 0x0C, kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E, kDataEnd = 0x0F,
};

// Little-endian encoding of MCAP's field types.
void u8(std::string& out, std::uint8_t v) { out.push_back(static_cast<char>(v)); }
template <class T>
void le(std::string& out, T v)
{
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out.push_back(static_cast<char>((static_cast<std::uint64_t>(v) >> (8 * i)) & 0xFFU));
  }
}
void str(std::string& out, const std::string& s)
{
  le<std::uint32_t>(out, static_cast<std::uint32_t>(s.size()));
  out += s;
}
void strMap(std::string& out, const std::map<std::string, std::string>& m)
{
  std::string body;
  for (const auto& [k, v] : m) {
    str(body, k);
    str(body, v);
  }
  str(out, body);  // a map is its byte length, then its entries
}
std::string record(Op op, const std::string& content)
{
  std::string out;
  u8(out, op);
  le<std::uint64_t>(out, content.size());
  return out + content;
}

std::string schemaRecord(const Schema& s)
{
  std::string c;
  le<std::uint16_t>(c, s.id);
  str(c, s.name);
  str(c, s.encoding);
  str(c, s.data);
  return record(kSchema, c);
}

std::string channelRecord(const Channel& ch)
{
  std::string c;
  le<std::uint16_t>(c, ch.id);
  le<std::uint16_t>(c, ch.schema_id);
  str(c, ch.topic);
  str(c, ch.message_encoding);
  strMap(c, ch.metadata);
  return record(kChannel, c);
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Writer

McapWriter::McapWriter(const std::filesystem::path& path, std::size_t chunk_size, std::string compression)
    : path_(path), chunk_size_(chunk_size), compression_(std::move(compression))
{
  if (!compression_.empty() && compression_ != "zstd") {
    throw BagError(path.string() + ": compression '" + compression_ + "': expected none or zstd");
  }
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) {
    throw BagError(path.string() + ": cannot create: " + std::strerror(errno));
  }
  put(std::string(kMagic, kMagicSize));
  std::string header;
  str(header, "");      // profile: none (the schemas say what the messages are)
  str(header, "quad");  // library
  put(record(kHeader, header));
  if (std::fflush(file_) != 0) {
    throw BagError(path_.string() + ": cannot write: " + std::strerror(errno));
  }
}

McapWriter::~McapWriter()
{
  try {
    close();
  } catch (const BagError&) {
  }
  if (file_ != nullptr) {
    std::fclose(file_);
  }
}

void McapWriter::put(std::string_view bytes)
{
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) {
    throw BagError(path_.string() + ": cannot write at byte " + std::to_string(offset_) + ": " + std::strerror(errno));
  }
  offset_ += bytes.size();
}

std::uint16_t McapWriter::addSchema(const std::string& name, const std::string& encoding, const std::string& data)
{
  Schema s{static_cast<std::uint16_t>(schemas_.size() + 1), name, encoding, data};  // 0 means "no schema"
  put(schemaRecord(s));
  schemas_.push_back(std::move(s));
  return schemas_.back().id;
}

std::uint16_t McapWriter::addChannel(std::uint16_t schema_id, const std::string& topic,
                                     const std::string& message_encoding,
                                     const std::map<std::string, std::string>& metadata)
{
  Channel c{static_cast<std::uint16_t>(channels_.size()), schema_id, topic, message_encoding, metadata};
  put(channelRecord(c));
  channels_.push_back(std::move(c));
  return channels_.back().id;
}

void McapWriter::write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time,
                       std::uint64_t publish_time, const std::uint8_t* data, std::size_t size)
{
  if (chunk_.empty()) {
    chunk_start_ = log_time;
    chunk_end_ = log_time;
  }
  chunk_start_ = std::min(chunk_start_, log_time);
  chunk_end_ = std::max(chunk_end_, log_time);
  chunk_index_[channel_id].emplace_back(log_time, chunk_.size());
  // The Message record straight into the chunk: a payload is copied once on its way.
  u8(chunk_, kMessage);
  le<std::uint64_t>(chunk_, 2 + 4 + 8 + 8 + size);
  le<std::uint16_t>(chunk_, channel_id);
  le<std::uint32_t>(chunk_, sequence);
  le<std::uint64_t>(chunk_, log_time);
  le<std::uint64_t>(chunk_, publish_time);
  chunk_.append(reinterpret_cast<const char*>(data), size);
  first_time_ = message_count_ == 0 ? log_time : std::min(first_time_, log_time);
  last_time_ = std::max(last_time_, log_time);
  ++message_count_;
  ++channel_counts_[channel_id];
  if (chunk_.size() >= chunk_size_) {
    flushChunk();
  }
}

void McapWriter::flushChunk()
{
  if (chunk_.empty()) {
    return;
  }
  const std::uint64_t chunk_offset = offset_;
  std::string_view stored = chunk_;
  if (compression_ == "zstd") {
    const std::size_t bound = ZSTD_compressBound(chunk_.size());
    if (compressed_.size() < bound) {
      compressed_.resize(bound);  // grows only: a buffer zeroed again for every chunk costs a copy
    }
    const std::size_t n = ZSTD_compress(compressed_.data(), compressed_.size(), chunk_.data(), chunk_.size(), 1);
    if (ZSTD_isError(n) != 0U) {
      throw BagError(path_.string() + ": zstd: " + ZSTD_getErrorName(n));
    }
    stored = std::string_view(compressed_.data(), n);
  }
  // The Chunk record's fields, then the stored records written from where they are.
  std::string head;
  u8(head, kChunk);
  le<std::uint64_t>(head, 8 + 8 + 8 + 4 + 4 + compression_.size() + 8 + stored.size());
  le<std::uint64_t>(head, chunk_start_);
  le<std::uint64_t>(head, chunk_end_);
  le<std::uint64_t>(head, chunk_.size());
  le<std::uint32_t>(head, crc32(chunk_.data(), chunk_.size()));
  str(head, compression_);
  le<std::uint64_t>(head, stored.size());
  put(head);
  put(stored);
  const std::uint64_t chunk_length = offset_ - chunk_offset;
  // One message index per channel, right after the chunk.
  const std::uint64_t index_start = offset_;
  std::string offsets;
  for (const auto& [channel, entries] : chunk_index_) {
    le<std::uint16_t>(offsets, channel);
    le<std::uint64_t>(offsets, offset_);
    std::string index;
    le<std::uint16_t>(index, channel);
    std::string body;
    for (const auto& [time, at] : entries) {
      le<std::uint64_t>(body, time);
      le<std::uint64_t>(body, at);
    }
    str(index, body);
    put(record(kMessageIndex, index));
  }
  std::string ci;
  le<std::uint64_t>(ci, chunk_start_);
  le<std::uint64_t>(ci, chunk_end_);
  le<std::uint64_t>(ci, chunk_offset);
  le<std::uint64_t>(ci, chunk_length);
  str(ci, offsets);
  le<std::uint64_t>(ci, offset_ - index_start);
  str(ci, compression_);
  le<std::uint64_t>(ci, stored.size());
  le<std::uint64_t>(ci, chunk_.size());
  chunk_indexes_ += record(kChunkIndex, ci);
  ++chunk_count_;
  chunk_.clear();
  chunk_index_.clear();
  if (std::fflush(file_) != 0) {
    throw BagError(path_.string() + ": cannot write: " + std::strerror(errno));
  }
}

void McapWriter::addMetadata(const std::string& name, const std::map<std::string, std::string>& values)
{
  flushChunk();  // metadata sits between chunks in the data section
  std::string content;
  str(content, name);
  strMap(content, values);
  const std::uint64_t at = offset_;
  put(record(kMetadata, content));
  std::string index;
  le<std::uint64_t>(index, at);
  le<std::uint64_t>(index, offset_ - at);
  str(index, name);
  metadata_indexes_ += record(kMetadataIndex, index);
  ++metadata_count_;
}

void McapWriter::close()
{
  if (closed_ || file_ == nullptr) {
    return;
  }
  closed_ = true;
  flushChunk();
  std::string data_end;
  le<std::uint32_t>(data_end, 0);  // the data section's CRC: not computed (chunks carry their own)
  put(record(kDataEnd, data_end));

  // Summary: groups of schemas, channels, statistics, chunk indexes, metadata indexes.
  const std::uint64_t summary_start = offset_;
  std::string summary;
  std::vector<std::tuple<Op, std::uint64_t, std::uint64_t>> groups;
  auto group = [&](Op op, const std::string& records) {
    if (!records.empty()) {
      groups.emplace_back(op, summary_start + summary.size(), records.size());
      summary += records;
    }
  };
  std::string schemas;
  for (const auto& s : schemas_) {
    schemas += schemaRecord(s);
  }
  group(kSchema, schemas);
  std::string channels;
  for (const auto& ch : channels_) {
    channels += channelRecord(ch);
  }
  group(kChannel, channels);
  std::string stats;
  le<std::uint64_t>(stats, message_count_);
  le<std::uint16_t>(stats, static_cast<std::uint16_t>(schemas_.size()));
  le<std::uint32_t>(stats, static_cast<std::uint32_t>(channels_.size()));
  le<std::uint32_t>(stats, 0);  // attachments
  le<std::uint32_t>(stats, metadata_count_);
  le<std::uint32_t>(stats, chunk_count_);
  le<std::uint64_t>(stats, first_time_);
  le<std::uint64_t>(stats, last_time_);
  std::string counts;
  for (const auto& [channel, n] : channel_counts_) {
    le<std::uint16_t>(counts, channel);
    le<std::uint64_t>(counts, n);
  }
  str(stats, counts);
  group(kStatistics, record(kStatistics, stats));
  group(kChunkIndex, chunk_indexes_);
  group(kMetadataIndex, metadata_indexes_);

  const std::uint64_t summary_offset_start = summary_start + summary.size();
  std::string offsets;
  for (const auto& [op, start, length] : groups) {
    std::string c;
    u8(c, op);
    le<std::uint64_t>(c, start);
    le<std::uint64_t>(c, length);
    offsets += record(kSummaryOffset, c);
  }
  std::string footer;
  le<std::uint64_t>(footer, summary.empty() ? 0 : summary_start);
  le<std::uint64_t>(footer, offsets.empty() ? 0 : summary_offset_start);
  // The summary CRC covers the summary, the offsets and the footer up to this field.
  std::string covered = summary + offsets;
  covered += static_cast<char>(kFooter);
  std::string length;
  le<std::uint64_t>(length, 20);
  covered += length + footer;
  le<std::uint32_t>(footer, crc32(covered.data(), covered.size()));
  put(summary);
  put(offsets);
  put(record(kFooter, footer));
  put(std::string(kMagic, kMagicSize));
  if (std::fflush(file_) != 0 || std::fclose(file_) != 0) {
    file_ = nullptr;
    throw BagError(path_.string() + ": cannot write: " + std::strerror(errno));
  }
  file_ = nullptr;
}

// ---------------------------------------------------------------------------------------
// Reader

namespace {

/// The largest chunk the writer makes: --chunk-size up to 1 GiB, and the message that ends it.
constexpr std::uint64_t kMaxChunkBytes = (std::uint64_t{1} << 30) + (std::uint64_t{32} << 20);

/// A zstd chunk's records. The buffer grows with what the data really decompresses to (never
/// to what the chunk merely claims), and that must be exactly `expected` bytes.
std::string inflateZstd(const std::uint8_t* stored, std::size_t size, std::uint64_t expected)
{
  if (expected > kMaxChunkBytes) {
    throw BagError("chunk claims " + std::to_string(expected) + " bytes uncompressed, more than any chunk holds");
  }
  const std::unique_ptr<ZSTD_DCtx, std::size_t (*)(ZSTD_DCtx*)> ctx(ZSTD_createDCtx(), ZSTD_freeDCtx);
  ZSTD_inBuffer in{stored, size, 0};
  std::string out;
  std::size_t produced = 0;
  std::size_t more = 1;  // ZSTD_decompressStream's hint: 0 once the frame is whole
  while (more != 0) {
    if (produced == out.size()) {
      if (out.size() > expected) {
        throw BagError("chunk decompresses to more than the " + std::to_string(expected) + " bytes it claims");
      }
      out.resize(static_cast<std::size_t>(std::min<std::uint64_t>(expected + 1, std::max<std::size_t>(2 * out.size(), 1 << 16))));
    }
    ZSTD_outBuffer o{out.data(), out.size(), produced};
    const std::size_t consumed = in.pos;
    more = ZSTD_decompressStream(ctx.get(), &o, &in);
    if (ZSTD_isError(more) != 0U) {
      throw BagError(std::string("chunk does not decompress (zstd: ") + ZSTD_getErrorName(more) + ")");
    }
    if (more != 0 && in.pos == consumed && o.pos == produced) {
      throw BagError("chunk's zstd data ends before its frame does");
    }
    produced = o.pos;
  }
  if (produced != expected || in.pos != size) {
    throw BagError("chunk decompresses to " + std::to_string(produced) + " bytes, not the " + std::to_string(expected) +
                   " it claims");
  }
  out.resize(produced);
  return out;
}

/// Reads fields from a byte range, throwing on running past its end.
class Cursor {
public:
  Cursor(const std::uint8_t* begin, std::size_t size, std::uint64_t base) : p_(begin), end_(begin + size), base_(base) {}

  template <class T>
  T le()
  {
    need(sizeof(T));
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      v |= static_cast<std::uint64_t>(p_[i]) << (8 * i);
    }
    p_ += sizeof(T);
    return static_cast<T>(v);
  }
  std::string str()
  {
    const auto n = le<std::uint32_t>();
    need(n);
    std::string s(reinterpret_cast<const char*>(p_), n);
    p_ += n;
    return s;
  }
  std::map<std::string, std::string> strMap()
  {
    const auto n = le<std::uint32_t>();
    need(n);
    Cursor body(p_, n, offset());
    p_ += n;
    std::map<std::string, std::string> m;
    while (!body.done()) {
      auto k = body.str();
      m[k] = body.str();
    }
    return m;
  }
  std::vector<std::uint8_t> rest()
  {
    std::vector<std::uint8_t> v(p_, end_);
    p_ = end_;
    return v;
  }
  const std::uint8_t* take(std::size_t n)
  {
    need(n);
    const auto* at = p_;
    p_ += n;
    return at;
  }
  bool done() const { return p_ == end_; }
  std::uint64_t offset() const { return base_; }

private:
  void need(std::size_t n) const
  {
    if (static_cast<std::size_t>(end_ - p_) < n) {
      throw BagError("a field runs past the end of its record");
    }
  }
  const std::uint8_t* p_;
  const std::uint8_t* end_;
  std::uint64_t base_;
};

/// Parses the records of [begin, begin + size); `base` is their offset in the file (for
/// messages) and `in_chunk` forbids records that cannot be inside a chunk.
void parseRecords(const std::uint8_t* begin, std::size_t size, std::uint64_t base, bool in_chunk, McapContents& out,
                  bool& footer_seen, std::uint64_t& good_end)
{
  std::size_t at = 0;
  while (at < size && !footer_seen) {
    if (size - at < 9) {
      throw BagError("at byte " + std::to_string(base + at) + ": truncated record header");
    }
    const std::uint8_t op = begin[at];
    std::uint64_t length = 0;
    for (int i = 0; i < 8; ++i) {
      length |= static_cast<std::uint64_t>(begin[at + 1 + static_cast<std::size_t>(i)]) << (8 * i);
    }
    if (length > size - at - 9) {
      throw BagError("at byte " + std::to_string(base + at) + ": record of " + std::to_string(length) +
                     " bytes runs past the end (truncated file?)");
    }
    Cursor c(begin + at + 9, static_cast<std::size_t>(length), base + at);
    try {
      switch (op) {
        case kSchema: {
          Schema s;
          s.id = c.le<std::uint16_t>();
          s.name = c.str();
          s.encoding = c.str();
          s.data = c.str();
          if (std::none_of(out.schemas.begin(), out.schemas.end(), [&](const Schema& x) { return x.id == s.id; })) {
            out.schemas.push_back(std::move(s));
          }
          break;
        }
        case kChannel: {
          Channel ch;
          ch.id = c.le<std::uint16_t>();
          ch.schema_id = c.le<std::uint16_t>();
          ch.topic = c.str();
          ch.message_encoding = c.str();
          ch.metadata = c.strMap();
          if (std::none_of(out.channels.begin(), out.channels.end(), [&](const Channel& x) { return x.id == ch.id; })) {
            out.channels.push_back(std::move(ch));
          }
          break;
        }
        case kMessage: {
          Message m;
          m.channel_id = c.le<std::uint16_t>();
          m.sequence = c.le<std::uint32_t>();
          m.log_time = c.le<std::uint64_t>();
          m.publish_time = c.le<std::uint64_t>();
          m.data = c.rest();
          if (std::none_of(out.channels.begin(), out.channels.end(),
                           [&](const Channel& x) { return x.id == m.channel_id; })) {
            throw BagError("message on channel " + std::to_string(m.channel_id) + ", which no channel record defined");
          }
          out.messages.push_back(std::move(m));
          break;
        }
        case kChunk: {
          if (in_chunk) {
            throw BagError("a chunk inside a chunk");
          }
          c.le<std::uint64_t>();
          c.le<std::uint64_t>();
          const auto uncompressed_size = c.le<std::uint64_t>();
          const auto crc = c.le<std::uint32_t>();
          const auto compression = c.str();
          const auto records_size = c.le<std::uint64_t>();
          const auto* stored = c.take(static_cast<std::size_t>(records_size));
          std::string inflated;
          const std::uint8_t* records = stored;
          if (compression == "zstd") {
            inflated = inflateZstd(stored, static_cast<std::size_t>(records_size), uncompressed_size);
            records = reinterpret_cast<const std::uint8_t*>(inflated.data());
          } else if (!compression.empty()) {
            throw BagError("chunk compressed with '" + compression + "', which this reader does not support");
          } else if (records_size != uncompressed_size) {
            throw BagError("chunk sizes disagree");
          }
          if (crc != 0 && crc32(records, static_cast<std::size_t>(uncompressed_size)) != crc) {
            throw BagError("chunk CRC mismatch (corrupt chunk)");
          }
          bool inner_footer = false;
          std::uint64_t inner_end = 0;
          McapContents inner;
          inner.channels = out.channels;
          inner.schemas = out.schemas;
          parseRecords(records, static_cast<std::size_t>(uncompressed_size), 0, true, inner, inner_footer, inner_end);
          for (auto& m : inner.messages) {
            out.messages.push_back(std::move(m));
          }
          out.channels = std::move(inner.channels);
          out.schemas = std::move(inner.schemas);
          ++out.chunks;
          break;
        }
        case kMetadata: {
          Metadata m;
          m.name = c.str();
          m.values = c.strMap();
          out.metadata.push_back(std::move(m));
          break;
        }
        case kFooter:
          if (in_chunk) {
            throw BagError("a footer inside a chunk");
          }
          footer_seen = true;
          break;
        case kHeader:
        case kMessageIndex:
        case kChunkIndex:
        case kStatistics:
        case kMetadataIndex:
        case kSummaryOffset:
        case kDataEnd:
          break;  // indexes and summaries repeat what the records say
        default:
          break;  // unknown opcodes are skipped, as the specification asks
      }
    } catch (const BagError& e) {
      const std::string what = e.what();
      throw BagError(what.starts_with("at byte ") ? what : "at byte " + std::to_string(base + at) + ": " + what);
    }
    at += 9 + static_cast<std::size_t>(length);
    good_end = base + at;
  }
}

}  // namespace

std::map<std::string, std::string> metadataValues(const McapContents& contents, std::string_view name)
{
  std::map<std::string, std::string> values;
  for (const auto& md : contents.metadata) {
    if (md.name == name) {
      values = md.values;
    }
  }
  return values;
}

McapContents readMcap(const std::filesystem::path& path, bool tolerant)
{
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw BagError(path.string() + ": cannot open: " + std::strerror(errno));
  }
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return readMcap(bytes, path.string(), tolerant);
}

McapContents readMcap(std::span<const std::uint8_t> bytes, const std::string& name, bool tolerant)
{
  McapContents out;
  if (bytes.size() < kMagicSize || std::memcmp(bytes.data(), kMagic, kMagicSize) != 0) {
    throw BagError(name + ": not an MCAP file (no MCAP magic at its start)");
  }
  bool footer = false;
  std::uint64_t good_end = kMagicSize;
  try {
    parseRecords(bytes.data() + kMagicSize, bytes.size() - kMagicSize, kMagicSize, false, out, footer, good_end);
    if (!footer) {
      throw BagError("at byte " + std::to_string(bytes.size()) + ": the file ends without a footer (truncated?)");
    }
    if (bytes.size() - good_end != kMagicSize || std::memcmp(bytes.data() + good_end, kMagic, kMagicSize) != 0) {
      throw BagError("at byte " + std::to_string(good_end) + ": no MCAP magic after the footer");
    }
    out.complete = true;
  } catch (const BagError& e) {
    if (!tolerant) {
      throw BagError(name + ": " + e.what());
    }
    out.problem = e.what();
  }
  out.good_bytes = good_end;
  return out;
}

McapContents recoverMcap(const std::filesystem::path& damaged, const std::filesystem::path& output)
{
  McapContents c = readMcap(damaged, true);
  McapWriter w(output);
  std::map<std::uint16_t, std::uint16_t> schema_ids{{0, 0}};  // ids are given anew, in order
  for (const auto& s : c.schemas) {
    schema_ids[s.id] = w.addSchema(s.name, s.encoding, s.data);
  }
  std::map<std::uint16_t, std::uint16_t> channel_ids;
  for (const auto& ch : c.channels) {
    const auto sid = schema_ids.find(ch.schema_id);
    channel_ids[ch.id] = w.addChannel(sid == schema_ids.end() ? 0 : sid->second, ch.topic, ch.message_encoding,
                                      ch.metadata);
  }
  for (const auto& m : c.messages) {
    w.write(channel_ids.at(m.channel_id), m.sequence, m.log_time, m.publish_time, m.data.data(), m.data.size());
  }
  for (const auto& md : c.metadata) {
    w.addMetadata(md.name, md.values);
  }
  w.close();
  return c;
}

}  // namespace quad::bag
