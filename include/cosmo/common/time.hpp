#pragma once
// Message time. The core never reads the wall clock: every time is a stamp carried by the data, as unsigned
// nanoseconds since the UNIX epoch (the JRL stamp unit) or as seconds (double) where arithmetic needs it.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace cosmo {

using StampNs = std::uint64_t;

inline double toSeconds(StampNs ns) { return static_cast<double>(ns) * 1e-9; }
inline StampNs toStampNs(double seconds) {
  return seconds <= 0.0 ? 0 : static_cast<StampNs>(std::llround(seconds * 1e9));
}

/// A stamp read from a file, in seconds: finite and within ROS time's range [0, 2^32) s (no bag message lies
/// outside it); otherwise throws std::runtime_error "<where>: stamp <value> s is not ...".
inline StampNs fileStamp(double seconds, const std::string& where) {
  if (!(seconds >= 0.0 && seconds < 4294967296.0))
    throw std::runtime_error(where + ": stamp " + std::to_string(seconds) +
                             " s is not a time between 0 and 2^32 s (ROS time's range)");
  return toStampNs(seconds);
}

}  // namespace cosmo
