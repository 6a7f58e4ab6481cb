// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Where a recording goes: one MCAP file, or parts when it is split by size or duration.

#include <cstdint>
#include <ctime>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <fmt/chrono.h>
#include <fmt/format.h>

#include "quad/bag/audit.hpp"
#include "quad/bag/mcap.hpp"
#include "quad/record/recorder.hpp"

namespace quad::record {

/// The recording's file, or files when it is split by size or duration: each part is a
/// whole MCAP file with every schema and channel (same ids in every part).
class RecordingFiles {
public:
  RecordingFiles(const RecordOptions& options, std::map<std::string, std::string> recording)
      : options_(options), recording_(std::move(recording))
  {
    base_ = options.output.empty() ? fmt::format("quad-{:%Y%m%d-%H%M%S}", fmt::localtime(std::time(nullptr)))
                                   : options.output;
    if (base_.ends_with(".mcap")) {
      base_.resize(base_.size() - 5);
    }
    open();
  }

  const std::string& current() const { return name_; }
  int parts() const { return part_ + 1; }
  std::uint64_t messages() const { return messages_; }

  std::uint16_t addSchema(const std::string& type, const std::string& idl)
  {
    schemas_.emplace_back(type, idl);
    return writer_->addSchema(type, "omgidl", idl);
  }

  std::uint16_t addChannel(std::uint16_t schema, const std::string& topic, const std::map<std::string, std::string>& md)
  {
    channels_.push_back({schema, topic, md});
    return writer_->addChannel(schema, topic, "cdr", md);
  }

  void write(std::uint16_t channel, std::uint32_t seq, std::uint64_t log_time, std::uint64_t publish,
             const std::vector<std::uint8_t>& payload)
  {
    const bool by_size = options_.split_size_mb > 0 &&
                         static_cast<double>(writer_->bytesWritten()) >= options_.split_size_mb * 1e6;
    const bool by_time = options_.split_duration_s > 0 && file_start_ != 0 &&
                         static_cast<double>(log_time - file_start_) * 1e-9 >= options_.split_duration_s;
    if (by_size || by_time) {
      writer_->close();
      ++part_;
      open();
      for (const auto& [type, idl] : schemas_) {
        writer_->addSchema(type, "omgidl", idl);
      }
      for (const auto& c : channels_) {
        writer_->addChannel(c.schema, c.topic, "cdr", c.metadata);
      }
    }
    if (file_start_ == 0) {
      file_start_ = log_time;
    }
    writer_->write(channel, seq, log_time, publish, payload.data(), payload.size());
    ++messages_;
  }

  void finish(const std::map<std::string, std::string>& loss)
  {
    writer_->addMetadata(std::string(bag::kLossMetadata), loss);
    writer_->close();
  }

private:
  void open()
  {
    name_ = split() ? fmt::format("{}_{:03d}.mcap", base_, part_) : base_ + ".mcap";
    writer_ = std::make_unique<bag::McapWriter>(name_, options_.chunk_size, options_.compression);
    auto md = recording_;
    md["part"] = std::to_string(part_);
    writer_->addMetadata("quad.recording", md);
    file_start_ = 0;
  }
  bool split() const { return options_.split_size_mb > 0 || options_.split_duration_s > 0; }

  struct ChannelDef {
    std::uint16_t schema;
    std::string topic;
    std::map<std::string, std::string> metadata;
  };
  const RecordOptions& options_;
  std::map<std::string, std::string> recording_;
  std::string base_;
  std::string name_;
  int part_ = 0;
  std::unique_ptr<bag::McapWriter> writer_;
  std::vector<std::pair<std::string, std::string>> schemas_;
  std::vector<ChannelDef> channels_;
  std::uint64_t file_start_ = 0;
  std::uint64_t messages_ = 0;
};

}  // namespace quad::record
