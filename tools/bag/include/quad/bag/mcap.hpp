// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// MCAP files (mcap.dev/spec, major version 0): a writer that produces chunked, indexed
/// files with a summary, and a reader that checks what it reads. No DDS: messages are bytes.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "quad/bag/crc32.hpp"

namespace quad::bag {

/// A problem with a file: names it, the byte offset and what is wrong.
class BagError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct Schema {
  std::uint16_t id = 0;
  std::string name;
  std::string encoding;  ///< "omgidl"
  std::string data;
};

struct Channel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;  ///< "cdr"
  std::map<std::string, std::string> metadata;
};

struct Message {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;      ///< [ns] when recorded
  std::uint64_t publish_time = 0;  ///< [ns] when published
  std::vector<std::uint8_t> data;
};

struct Metadata {
  std::string name;
  std::map<std::string, std::string> values;
};

class McapWriter {
public:
  /// Creates `path`; throws BagError naming it when it cannot. Messages are grouped in
  /// chunks of about `chunk_size` bytes; each complete chunk is flushed to the file, so a
  /// writer killed mid-run leaves every chunk before the one it was filling.
  /// `compression`: "" (none) or "zstd" (each chunk's records, at level 1).
  explicit McapWriter(const std::filesystem::path& path, std::size_t chunk_size = 1 << 20,
                      std::string compression = "");
  ~McapWriter();  // closes (summary and footer) if close() was not called; never throws
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  std::uint16_t addSchema(const std::string& name, const std::string& encoding, const std::string& data);
  std::uint16_t addChannel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                           const std::map<std::string, std::string>& metadata);
  void write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time, std::uint64_t publish_time,
             const std::uint8_t* data, std::size_t size);
  void addMetadata(const std::string& name, const std::map<std::string, std::string>& values);

  /// Writes the last chunk, the summary and the footer. Throws BagError on a write error
  /// (a full disk, say), naming the file.
  void close();

  std::uint64_t messages() const { return message_count_; }
  std::uint64_t bytesWritten() const { return offset_; }

private:
  void put(std::string_view bytes);  // to the file, counted
  void flushChunk();

  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  std::size_t chunk_size_;
  std::string compression_;
  std::uint64_t offset_ = 0;
  std::string chunk_;  // records of the open chunk
  std::vector<char> compressed_;  // the open chunk compressed, when it is (never shrinks)
  std::uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;  // channel -> (time, offset)
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::string chunk_indexes_;     // ChunkIndex records, for the summary
  std::string metadata_indexes_;  // MetadataIndex records
  std::uint32_t chunk_count_ = 0;
  std::uint32_t metadata_count_ = 0;
  std::uint64_t message_count_ = 0;
  std::uint64_t first_time_ = 0, last_time_ = 0;
  std::map<std::uint16_t, std::uint64_t> channel_counts_;
  bool closed_ = false;
};

/// What a reader found in a file.
struct McapContents {
  std::vector<Schema> schemas;
  std::vector<Channel> channels;
  std::vector<Message> messages;  ///< in file order
  std::vector<Metadata> metadata;
  std::uint32_t chunks = 0;
  bool complete = false;   ///< the file ends with its footer and magic
  std::string problem;     ///< why reading stopped early (tolerant mode), else empty
  std::uint64_t good_bytes = 0;  ///< bytes up to the end of the last complete record read
};

/// The values of the last metadata record called `name` (empty when there is none).
std::map<std::string, std::string> metadataValues(const McapContents& contents, std::string_view name);

/// Reads a whole file, checking the magic, every record's bounds and every chunk's CRC.
/// Strict: throws BagError "<file>: at byte N: <what>" at the first problem. Tolerant: stops
/// there and returns what came before, with `problem` set (what `quad bag recover` needs).
McapContents readMcap(const std::filesystem::path& path, bool tolerant = false);
/// The same for bytes in memory; `name` stands for the file in errors.
McapContents readMcap(std::span<const std::uint8_t> bytes, const std::string& name, bool tolerant = false);

/// Rewrites what can be read of `damaged` (every complete chunk; a writer killed with
/// SIGKILL leaves no summary or footer) as a whole file at `output`: same schemas, channels
/// and metadata, messages in their order, a new index, summary and footer. Returns the
/// contents read (`problem` says what stopped the reading, empty if the file was whole).
/// Throws BagError when `damaged` is not MCAP at all or `output` cannot be written.
McapContents recoverMcap(const std::filesystem::path& damaged, const std::filesystem::path& output);

}  // namespace quad::bag
