#pragma once
// Decompression of a ROS 1 bag chunk (bz2 through libbz2, lz4 through liblz4's frame format, which roslz4 writes),
// checked: the data must decompress to exactly the chunk header's `size`, else a Ros1BagError naming the chunk.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "cosmo/trials/ros1_bag.hpp"
#include "ros1_records.hpp"

namespace cosmo::trials::ros1 {

/// Decompresses `n` stored bytes into `out` (resized to `size`). The output grows as the stream produces it, so a
/// damaged `size` costs no memory the data does not fill.
void decompressChunk(Ros1Compression compression, const std::uint8_t* in, std::size_t n, std::uint32_t size,
                     std::vector<std::uint8_t>& out, const Place& place);

}  // namespace cosmo::trials::ros1
