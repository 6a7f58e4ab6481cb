// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant_messages/faults.hpp"

#include <cmath>

#include "quad/common/time.hpp"
#include "quad/dds/geometry_messages.hpp"

namespace quad::plant {

using dds::toMessage;

std::optional<Fault> faultFrom(const msg::FaultCommand& c, std::int64_t now_ns, std::string& why_not)
{
  Fault f;
  f.id = c.fault_id();
  f.start_ns = now_ns;
  f.duration_ns = c.duration_s() > 0.0 && std::isfinite(c.duration_s()) ? common::toNanoseconds(c.duration_s()) : 0;
  if (f.id == 0) {
    why_not = "fault_id 0 is invalid";
    return std::nullopt;
  }
  if (!std::isfinite(c.magnitude())) {
    why_not = "magnitude is not finite";
    return std::nullopt;
  }
  const auto sensor = [&]() -> bool {
    const auto s = parseSensor(c.target().to_string());
    if (!s) {
      why_not = "target '" + c.target().to_string() + "' is not a plant sensor (" + sensorNames() + ")";
      return false;
    }
    f.sensor = *s;
    return true;
  };
  switch (c.kind()) {
    case msg::FAULT_MOTOR_FAILURE:
      if (c.index() < 0 || c.index() > 3 || c.magnitude() < 0.0 || c.magnitude() > 1.0) {
        why_not = "motor faults need index 0..3 and a remaining efficiency in [0, 1]";
        return std::nullopt;
      }
      f.kind = Fault::Kind::kMotor;
      f.rotor = c.index();
      f.magnitude = c.magnitude();
      return f;
    case msg::FAULT_SENSOR_DROPOUT:
      f.kind = Fault::Kind::kSensorDropout;
      return sensor() ? std::optional(f) : std::nullopt;
    case msg::FAULT_SENSOR_STUCK:
      f.kind = Fault::Kind::kSensorStuck;
      return sensor() ? std::optional(f) : std::nullopt;
    case msg::FAULT_SENSOR_NOISE:
      if (c.magnitude() < 0.0) {
        why_not = "noise std dev must be >= 0";
        return std::nullopt;
      }
      f.kind = Fault::Kind::kSensorNoise;
      f.magnitude = c.magnitude();
      return sensor() ? std::optional(f) : std::nullopt;
    case msg::FAULT_SENSOR_OFFSET: {
      const Eigen::Vector3d v(c.vector_W().x(), c.vector_W().y(), c.vector_W().z());
      if (!v.allFinite()) {
        why_not = "sensor offset is not finite";
        return std::nullopt;
      }
      f.kind = Fault::Kind::kSensorOffset;
      f.offset = v;
      return sensor() ? std::optional(f) : std::nullopt;
    }
    case msg::FAULT_WIND_GUST:
    case msg::FAULT_PUSH: {
      const bool gust = c.kind() == msg::FAULT_WIND_GUST;
      const Eigen::Vector3d v(c.vector_W().x(), c.vector_W().y(), c.vector_W().z());
      if (!v.allFinite()) {
        why_not = gust ? "wind vector is not finite" : "push force is not finite";
        return std::nullopt;
      }
      f.kind = gust ? Fault::Kind::kWindGust : Fault::Kind::kPush;
      (gust ? f.wind_W : f.force_W) = v;
      return f;
    }
    case msg::FAULT_CELL_LOSS:
      if (c.index() < 1 || c.index() > 16) {
        why_not = "cell loss needs index 1..16 (the cells that fail)";
        return std::nullopt;
      }
      f.kind = Fault::Kind::kCellLoss;
      f.cells = c.index();
      return f;
    default:
      why_not = "this kind is not applied by the plant (datagram faults need its fault layer: QUAD_FAULT_LAYER=1)";
      return std::nullopt;
  }
}

msg::FaultCommand toCommand(const Fault& f)
{
  msg::FaultCommand c;
  c.fault_id(f.id);
  c.module_name("plant");
  c.index(-1);
  c.duration_s(common::toSeconds(f.duration_ns));
  switch (f.kind) {
    case Fault::Kind::kMotor:
      c.kind(msg::FAULT_MOTOR_FAILURE);
      c.index(f.rotor);
      c.magnitude(f.magnitude);
      break;
    case Fault::Kind::kSensorDropout:
      c.kind(msg::FAULT_SENSOR_DROPOUT);
      break;
    case Fault::Kind::kSensorStuck:
      c.kind(msg::FAULT_SENSOR_STUCK);
      break;
    case Fault::Kind::kSensorNoise:
      c.kind(msg::FAULT_SENSOR_NOISE);
      c.magnitude(f.magnitude);
      break;
    case Fault::Kind::kSensorOffset:
      c.kind(msg::FAULT_SENSOR_OFFSET);
      c.vector_W(toMessage(f.offset));
      break;
    case Fault::Kind::kWindGust:
      c.kind(msg::FAULT_WIND_GUST);
      c.vector_W(toMessage(f.wind_W));
      break;
    case Fault::Kind::kPush:
      c.kind(msg::FAULT_PUSH);
      c.vector_W(toMessage(f.force_W));
      break;
    case Fault::Kind::kCellLoss:
      c.kind(msg::FAULT_CELL_LOSS);
      c.index(f.cells);
      break;
  }
  if (f.kind == Fault::Kind::kSensorDropout || f.kind == Fault::Kind::kSensorStuck ||
      f.kind == Fault::Kind::kSensorNoise || f.kind == Fault::Kind::kSensorOffset) {
    c.target(std::string(toString(f.sensor)));
  }
  return c;
}

}  // namespace quad::plant
