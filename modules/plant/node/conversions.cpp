// SPDX-License-Identifier: BSD-3-Clause
#include "conversions.hpp"

#include <cmath>
#include <limits>

#include "quad/common/time.hpp"
#include "quad/dds/geometry_messages.hpp"

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

msg::PositionFix toMessage(const PositionReading& r)
{
  msg::PositionFix m;
  m.header().stamp_ns(r.t_ns);
  m.p_W(toMessage(r.fix.p_W));
  m.std_dev(r.fix.std_dev);
  return m;
}

msg::BaroAltitude toMessage(const BaroReading& r)
{
  msg::BaroAltitude m;
  m.header().stamp_ns(r.t_ns);
  m.altitude(r.altitude);
  m.std_dev(r.std_dev);
  return m;
}

msg::Range toMessage(const RangeReading& r)
{
  msg::Range m;
  m.header().stamp_ns(r.t_ns);
  m.range(r.range.value_or(std::numeric_limits<double>::infinity()));
  m.max_range(r.max_range);
  m.std_dev(r.std_dev);
  return m;
}

msg::MagneticField toMessage(const MagReading& r)
{
  msg::MagneticField m;
  m.header().stamp_ns(r.t_ns);
  m.field_B(toMessage(r.field_B));
  m.std_dev(r.std_dev);
  return m;
}

msg::BatteryState toMessage(const BatteryReading& r)
{
  msg::BatteryState m;
  m.header().stamp_ns(r.t_ns);
  m.voltage(r.voltage);
  m.current(r.current);
  m.charge(r.charge);
  m.capacity(r.capacity);
  m.cells(static_cast<std::uint16_t>(r.cells));
  return m;
}

msg::PointCloud toMessage(const DepthReading& r, double max_range)
{
  msg::PointCloud m;
  m.header().stamp_ns(r.t_ns);
  m.frame_id("depth_front");
  m.sensor_p_B(toMessage(r.sensor_B.p));
  m.sensor_q_BS(toMessage(r.sensor_B.q));
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
    case SimEventRecord::Kind::kCrash:
      m.kind(msg::SIM_EVENT_CRASH);
      break;
  }
  m.p_W(toMessage(e.p_W));
  m.subject_id(e.subject_id);
  m.detail(e.detail.substr(0, 256));
  return m;
}

}  // namespace quad::plant
