#pragma once
// A stamp read from a file (TUM, MCD, CU-Multi, KITTI references), checked before it is converted.
#include <stdexcept>
#include <string>

#include "cosmo/common/time.hpp"

namespace cosmo {

/// A stamp read from a file, in seconds: finite and within ROS time's range [0, 2^32) s (no bag message lies
/// outside it); otherwise throws std::runtime_error "<where>: stamp <value> s is not ...".
inline StampNs fileStamp(double seconds, const std::string& where) {
  if (!(seconds >= 0.0 && seconds < 4294967296.0))
    throw std::runtime_error(where + ": stamp " + std::to_string(seconds) +
                             " s is not a time between 0 and 2^32 s (ROS time's range)");
  return toStampNs(seconds);
}

}  // namespace cosmo
