// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Samples typed by a user, for any topic: values read from YAML and checked against the
/// topic's IDL, and encoded as CDR with the header a publisher fills. `quad topic pub` and
/// the fault tool's bad inputs send them.

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "quad/dds/raw_type.hpp"
#include "quad/dds/topic.hpp"

namespace quad::topic {

/// The fields of a sample of `info`'s type read from YAML `values` (as `quad topic pub`
/// takes them); throws std::invalid_argument naming the topic, the field and the value when
/// they do not make a sample.
nlohmann::ordered_json sampleValues(const dds::TopicInfo& info, const std::string& values);

/// `sample` as CDR, its Header filled where the values leave it unset. `enforce_bounds`
/// false writes strings and sequences past their IDL bounds as given (fault injection).
dds::RawSample encodeSample(const dds::TopicInfo& info, nlohmann::ordered_json sample, std::int64_t stamp_ns,
                            std::uint64_t seq, std::uint32_t vehicle_id, bool enforce_bounds = true);

}  // namespace quad::topic
