#include "cosmo/trials/ros1_point_cloud.hpp"

#include <stdexcept>

#include "cloud_members.hpp"
#include "cosmo/common/byte_cursor.hpp"

namespace cosmo::trials {

namespace {

/// A malformed ROS 1 PointCloud2, named with the field and the byte offset.
struct Ros1CloudFail {
  const std::string& source;
  std::size_t size;
  [[noreturn]] void operator()(const char* what, const std::string& why, std::size_t at) const {
    throw std::runtime_error(source + ": malformed PointCloud2 at " + what + " (byte " + std::to_string(at) + " of " +
                             std::to_string(size) + "): " + why);
  }
};

constexpr std::size_t kFieldMinBytes = 4 + 4 + 1 + 4;  ///< empty name, offset, datatype, count

}  // namespace

CloudView parseRos1PointCloud2(const std::uint8_t* message, std::size_t size, const std::string& source) {
  ByteCursor in(message, size, Ros1CloudFail{source, size});
  CloudView view;
  CloudLayout& L = view.layout;
  in.value<std::uint32_t>("header.seq");
  const auto sec = in.value<std::uint32_t>("header.stamp.sec");
  const auto nsec = in.value<std::uint32_t>("header.stamp.nsec");
  L.stamp = static_cast<StampNs>(sec) * 1000000000ULL + nsec;
  L.frame_id = in.string("header.frame_id");
  readCloudMembers(in, view, [&](std::uint32_t nfields) {
    if (nfields > in.left() / kFieldMinBytes)
      in.fail("fields", std::to_string(nfields) + " fields cannot fit in " + std::to_string(in.left()) + " bytes");
  });
  return view;
}

DecodeCounts decodeRos1PointCloud2(const std::uint8_t* message, std::size_t size, bool stamp_at_end,
                                   const std::string& source, Scan& scan, CloudLayout& layout) {
  CloudView v = parseRos1PointCloud2(message, size, source);
  const DecodeCounts counts = decodeCloud(v.layout, v.data, v.bytes, stamp_at_end, source, scan);
  layout = std::move(v.layout);
  return counts;
}

}  // namespace cosmo::trials
