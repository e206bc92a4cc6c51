#include "cosmo/frontend/odometry_source.hpp"

#include <stdexcept>

namespace cosmo::frontend {

OdometryKind parseOdometryKind(const std::string& name) {
  if (name == "loam") return OdometryKind::Loam;
  if (name == "reference") return OdometryKind::Reference;
  if (name == "external") return OdometryKind::External;
  throw std::invalid_argument("odometry must be loam, reference or external, got '" + name + "'");
}

const char* odometryKindName(OdometryKind kind) {
  switch (kind) {
    case OdometryKind::Loam: return "loam";
    case OdometryKind::Reference: return "reference";
    case OdometryKind::External: return "external";
  }
  return "?";
}

OdometrySource::OdometrySource(OdometryKind kind, ReferenceArrival arrival, StampNs reference_tolerance)
    : kind_(kind), arrival_(arrival), reference_tolerance_(reference_tolerance) {}

OdometryChoice OdometrySource::choose(StampNs stamp, const Trajectory& reference) const {
  OdometryChoice c;
  switch (kind_) {
    case OdometryKind::Loam: return c;
    case OdometryKind::Reference: {
      if (arrival_ == ReferenceArrival::Whole) {
        if (reference.empty()) return c;  // a robot without a reference: LOAM, as it was told
        c.use = OdometryChoice::Use::Pose;
        c.pose = reference.atClamped(stamp);
        return c;
      }
      if (const std::optional<Pose3> p = reference.atWithin(stamp, reference_tolerance_)) {
        c.use = OdometryChoice::Use::Pose;
        c.pose = *p;
      } else {
        c.notice = "no reference pose at the scan stamp; using LOAM";
      }
      return c;
    }
    case OdometryKind::External: {
      if (const std::optional<Pose3> p = external_.at(stamp)) {
        c.use = OdometryChoice::Use::Pose;
        c.pose = *p;
      } else {
        c.use = OdometryChoice::Use::Drop;
        c.notice = "no external odometry at the scan stamp; scan dropped";
      }
      return c;
    }
  }
  return c;
}

}  // namespace cosmo::frontend
