#pragma once
// Message time. The core never reads the wall clock: every time is a stamp carried by the data, as unsigned
// nanoseconds since the UNIX epoch (the JRL stamp unit) or as seconds (double) where arithmetic needs it.
#include <cmath>
#include <cstdint>

namespace cosmo {

using StampNs = std::uint64_t;

inline double toSeconds(StampNs ns) { return static_cast<double>(ns) * 1e-9; }
inline StampNs toStampNs(double seconds) {
  return seconds <= 0.0 ? 0 : static_cast<StampNs>(std::llround(seconds * 1e9));
}

}  // namespace cosmo
