#pragma once
// Query-side helpers: moving query points into the anchor frame and results back out, and the
// argument checks every query shares.

#include "core/tree/tree.hpp"

#include <eco/types.hpp>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace eco::detail {

/// The world position of `q` given in `frame`.
inline Eigen::Vector3d world_of(const Tree& t, const Eigen::Vector3d& q, Frame frame) {
  const Eigen::Isometry3d& pose = t.motion().pose;
  switch (frame) {
    case Frame::World: return q;
    case Frame::Ego: return q + pose.translation();
    case Frame::Sensor: return pose * q;
  }
  return q;
}

/// The pose of `frame` in the world: where the sensor is (its axes for Sensor, the world's for Ego).
inline Eigen::Isometry3d world_T_frame(const Tree& t, Frame frame) {
  Eigen::Isometry3d pose = t.motion().pose;
  if (frame == Frame::World) return Eigen::Isometry3d::Identity();
  if (frame == Frame::Ego) pose.linear().setIdentity();
  return pose;
}

/// `q` (given in `frame`) in the anchor frame, where stored points live.
inline std::array<double, 3> to_anchor_frame(const Tree& t, const Eigen::Vector3d& q, Frame frame) {
  const Eigen::Vector3d w = world_of(t, q, frame);
  const Eigen::Vector3d o = t.motion().anchor;
  return {w[0] - o[0], w[1] - o[1], w[2] - o[2]};
}

/// A stored point expressed in `frame`.
inline Eigen::Vector3d from_stored(const Tree& t, const std::array<float, 3>& p, Frame frame) {
  const Motion& m = t.motion();
  const Eigen::Vector3d w = m.to_world(p);
  if (frame == Frame::World) return w;
  const Eigen::Vector3d d = w - m.pose.translation();
  return frame == Frame::Ego ? d : Eigen::Vector3d(m.pose.linear().transpose() * d);
}

/// The attributes of stored point `s` as the caller gave them (zero where not kept).
inline PointAttributes attributes_of(const Tree& t, const StoredPoint& s) {
  return {s.id, s.intensity, t.points().columns().times ? t.motion().clock.seconds(s.time) : 0.0};
}

inline void require_finite(const Eigen::Vector3d& v, const char* what, const char* name) {
  if (!v.allFinite()) {
    std::ostringstream s;
    s << "eco::EgoOctree::" << what << ": " << name << " is not finite: [" << v.transpose() << "]";
    throw std::invalid_argument(s.str());
  }
}

inline void require_positive(double v, const char* what, const char* name, bool allow_zero) {
  if (!std::isfinite(v) || v < 0.0 || (!allow_zero && v == 0.0)) {
    throw std::invalid_argument(std::string("eco::EgoOctree::") + what + ": " + name + " = " +
                                std::to_string(v) + " must be finite and " +
                                (allow_zero ? ">= 0" : "> 0"));
  }
}

/// Walks the leaves below `id`. keep(bounds) says 0 = skip the subtree, 1 = look inside,
/// 2 = take the whole subtree; visit(point, whole) sees every point of the leaves reached, with
/// `whole` true when an ancestor was taken whole (the point needs no test).
template <class Keep, class Visit>
void walk_leaves(const Tree& t, std::uint32_t id, Keep&& keep, Visit&& visit, bool whole = false) {
  const Node& n = t.nodes()[id];
  if (n.count == 0) return;
  if (!whole) {
    const int verdict = keep(n.bounds);
    if (verdict == 0) return;
    whole = verdict == 2;
  }
  if (n.leaf) {
    t.points().for_each(n.link, n.count, [&](const StoredPoint& s) { visit(s, whole); });
    return;
  }
  t.nodes().for_each_child(id, [&](int, std::uint32_t ch) { walk_leaves(t, ch, keep, visit, whole); });
}

}  // namespace eco::detail
