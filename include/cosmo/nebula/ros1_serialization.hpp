#pragma once
// ROS 1 wire format of pose_graph_msgs/PoseGraph (little-endian; strings and variable arrays prefixed by a
// uint32 length, fixed arrays such as float64[36] not; bool one byte), decoded from and encoded to the raw
// bytes a bag stores. No ROS dependency: the bag container is read in src/ros/, the bytes decoded here.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosmo/nebula/pose_graph_msg.hpp"

namespace cosmo::nebula {

/// A message whose bytes do not match the layout. what() names the field and the byte offset, e.g.
/// "nodes[3].covariance at byte 412: message ends (needs 288 bytes, 96 left)".
class DecodeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Decode one serialized PoseGraph. Throws DecodeError on truncation, trailing bytes, a bool that is not 0/1
/// or an array length larger than the bytes left could hold.
PoseGraph decodePoseGraph(const std::uint8_t* data, std::size_t size);
inline PoseGraph decodePoseGraph(const std::vector<std::uint8_t>& bytes) {
  return decodePoseGraph(bytes.data(), bytes.size());
}

/// The serialized bytes of a PoseGraph (what roscpp would write).
std::vector<std::uint8_t> encodePoseGraph(const PoseGraph& graph);

}  // namespace cosmo::nebula
