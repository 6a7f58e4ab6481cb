// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// quad::geometry values ⇄ the IDL's Vector3 and Quaternion (both scalar first): one place
/// for the field-by-field copies every node needs.

#include <quad/msg/Quaternion.h>
#include <quad/msg/Vector3.h>

#include "quad/geometry/quaternion.hpp"

namespace quad::dds {

inline msg::Vector3 toMessage(const geometry::Vector3& v)
{
  msg::Vector3 out;
  out.x(v.x());
  out.y(v.y());
  out.z(v.z());
  return out;
}

inline msg::Quaternion toMessage(const geometry::Quaternion& q)
{
  msg::Quaternion out;
  out.w(q.w);
  out.x(q.x);
  out.y(q.y);
  out.z(q.z);
  return out;
}

inline geometry::Vector3 toVector(const msg::Vector3& v) { return {v.x(), v.y(), v.z()}; }

inline geometry::Quaternion toQuaternion(const msg::Quaternion& q) { return {q.w(), q.x(), q.y(), q.z()}; }

}  // namespace quad::dds
