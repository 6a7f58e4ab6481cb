#include "conversions.hpp"

#include "quad/dds/geometry_messages.hpp"

#include <cmath>

#include "quad/common/time.hpp"

namespace quad::plant {

using dds::toMessage;

msg::VehicleState toMessage(const StateSample& s)
{
  msg::VehicleState m;
  m.header().stamp_ns(s.t_ns);
  m.p_W(toMessage(s.state.p_W));
  m.v_W(toMessage(s.state.v_W));
  m.q_WB(toMessage(s.state.q_WB));
  m.w_B(toMessage(s.state.w_B));
  m.a_W(toMessage(s.a_W));
  m.landed(s.state.landed);
  return m;
}

msg::Imu toMessage(const ImuReading& r)
{
  msg::Imu m;
  m.header().stamp_ns(r.t_ns);
  m.specific_force_B(toMessage(r.sample.specific_force_B));
  m.angular_rate_B(toMessage(r.sample.angular_rate_B));
  return m;
}

msg::PointCloud toMessage(const DepthReading& r, double max_range)
{
  msg::PointCloud m;
  m.header().stamp_ns(r.t_ns);
  m.frame_id("depth_front");
  m.sensor_p_W(toMessage(r.scan.sensor_W.p));
  m.sensor_q_WS(toMessage(r.scan.sensor_W.q));
  m.max_range(static_cast<float>(max_range));
  m.points().reserve(r.scan.points_S.size());
  for (const auto& p : r.scan.points_S) {
    msg::Point3f point;
    point.x(p.x());
    point.y(p.y());
    point.z(p.z());
    m.points().push_back(point);
  }
  return m;
}

msg::SimEvent toMessage(const SimEventRecord& e)
{
  msg::SimEvent m;
  m.header().stamp_ns(e.t_ns);
  switch (e.kind) {
    case SimEventRecord::Kind::kCollision:
      m.kind(msg::SIM_EVENT_COLLISION);
      break;
    case SimEventRecord::Kind::kGroundContact:
      m.kind(msg::SIM_EVENT_GROUND_CONTACT);
      break;
    case SimEventRecord::Kind::kTakeoff:
      m.kind(msg::SIM_EVENT_TAKEOFF);
      break;
    case SimEventRecord::Kind::kFaultApplied:
      m.kind(msg::SIM_EVENT_FAULT_APPLIED);
      break;
    case SimEventRecord::Kind::kFaultCleared:
      m.kind(msg::SIM_EVENT_FAULT_CLEARED);
      break;
  }
  m.p_W(toMessage(e.p_W));
  m.subject_id(e.subject_id);
  m.detail(e.detail.substr(0, 256));
  return m;
}

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
      why_not = "target '" + c.target().to_string() + "' is not a plant sensor (depth, imu, state)";
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
    case msg::FAULT_WIND_GUST: {
      const Vector3 w(c.vector_W().x(), c.vector_W().y(), c.vector_W().z());
      if (!w.allFinite()) {
        why_not = "wind vector is not finite";
        return std::nullopt;
      }
      f.kind = Fault::Kind::kWindGust;
      f.wind_W = w;
      return f;
    }
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
    case Fault::Kind::kWindGust:
      c.kind(msg::FAULT_WIND_GUST);
      c.vector_W(toMessage(f.wind_W));
      break;
  }
  if (f.kind == Fault::Kind::kSensorDropout || f.kind == Fault::Kind::kSensorStuck ||
      f.kind == Fault::Kind::kSensorNoise) {
    c.target(std::string(toString(f.sensor)));
  }
  return c;
}

}  // namespace quad::plant
