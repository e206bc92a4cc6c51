#pragma once
// The radio payload of a keyframe: the scan's [x, y, z] float32 buffer (12 bytes per point, little-endian,
// point after point) compressed with liblzma as an .xz stream (preset 6, the `xz` command's default, CRC64).
// Only the points travel: the decompressed scan has no stamp, intensity, time or ring.
#include <cstdint>
#include <string>
#include <vector>

#include "cosmo/common/scan.hpp"

namespace cosmo::comm {

/// Uncompressed payload size S of a scan: 12 bytes per point.
inline std::size_t rawPayloadBytes(const Scan& scan) { return 12 * scan.size(); }

/// xz-compress the scan's points. Throws std::runtime_error on a liblzma failure.
std::vector<std::uint8_t> compressScan(const Scan& scan, std::uint32_t preset = 6);
/// Inverse of compressScan; throws std::runtime_error when the bytes are not an xz stream of whole points.
Scan decompressScan(const std::vector<std::uint8_t>& bytes);

}  // namespace cosmo::comm
