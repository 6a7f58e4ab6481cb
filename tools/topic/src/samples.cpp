// SPDX-License-Identifier: BSD-3-Clause
#include "quad/topic/samples.hpp"

#include <stdexcept>

#include "quad/common/time.hpp"
#include "quad/introspection/cdr.hpp"
#include "quad/topic/text_format.hpp"

namespace quad::topic {

nlohmann::ordered_json sampleValues(const dds::TopicInfo& info, const std::string& values)
{
  nlohmann::ordered_json value;
  try {
    value = yamlToJson(values);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("values '" + values + "': " + e.what());
  }
  if (!value.is_object()) {
    throw std::invalid_argument("values '" + values + "': expected a map of fields");
  }
  // Encoded once before any DDS work, so a typo costs nothing.
  try {
    introspection::encodeCdr(introspection::quadSchema(), info.type_name, value);
  } catch (const introspection::EncodeError& e) {
    throw std::invalid_argument(std::string(info.name) + ": " + e.what());
  }
  return value;
}

dds::RawSample encodeSample(const dds::TopicInfo& info, nlohmann::ordered_json sample, std::int64_t stamp_ns,
                            std::uint64_t seq, std::uint32_t vehicle_id, bool enforce_bounds)
{
  // The header is the publisher's to fill, as Publisher<T> does for the modules, except what
  // the values set on purpose.
  auto& header = sample["header"];
  const auto fill = [&](const char* key, auto v) {
    if (!header.contains(key)) {
      header[key] = v;
    }
  };
  fill("stamp_ns", stamp_ns);
  fill("publish_ns", common::wallTimeNs());
  fill("seq", seq);
  fill("vehicle_id", vehicle_id);
  return dds::RawSample{
      introspection::encodeCdr(introspection::quadSchema(), info.type_name, sample, {.enforce_bounds = enforce_bounds})};
}

}  // namespace quad::topic
