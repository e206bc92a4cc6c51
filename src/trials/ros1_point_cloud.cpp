#include "cosmo/trials/ros1_point_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "cloud_members.hpp"
#include "cosmo/common/byte_cursor.hpp"
#include "cosmo/trials/ros1_bag.hpp"

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

/// A malformed Livox CustomMsg, named with the member and the byte offset.
struct LivoxFail {
  const std::string& source;
  std::size_t size;
  [[noreturn]] void operator()(const char* what, const std::string& why, std::size_t at) const {
    throw std::runtime_error(source + ": malformed livox_ros_driver/CustomMsg at " + what + " (byte " +
                             std::to_string(at) + " of " + std::to_string(size) + "): " + why);
  }
};

constexpr std::uint32_t kLivoxPointBytes = 4 + 3 * 4 + 3;  ///< offset_time, x y z, reflectivity tag line

/// The layout of a CustomMsg's points (CustomPoint, packed).
const std::vector<PointField>& livoxPointFields() {
  auto type = [](PointType t) { return static_cast<std::uint8_t>(t); };
  static const std::vector<PointField> fields{
      {"offset_time", 0, type(PointType::UInt32), 1},  {"x", 4, type(PointType::Float32), 1},
      {"y", 8, type(PointType::Float32), 1},           {"z", 12, type(PointType::Float32), 1},
      {"reflectivity", 16, type(PointType::UInt8), 1}, {"tag", 17, type(PointType::UInt8), 1},
      {"line", 18, type(PointType::UInt8), 1}};
  return fields;
}

bool isLivoxCustomMsg(const std::string& type) {
  return type == "livox_ros_driver/CustomMsg" || type == "livox_ros_driver2/CustomMsg";
}

template <typename T>
void put(std::vector<std::uint8_t>& out, const T& v) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
  out.insert(out.end(), p, p + sizeof v);
}

}  // namespace

const char* const kLivoxCustomMsgDefinition =
    "Header header\n"
    "uint64 timebase\n"
    "uint32 point_num\n"
    "uint8 lidar_id\n"
    "uint8[3] rsvd\n"
    "CustomPoint[] points\n"
    "\n"
    "================================================================================\n"
    "MSG: std_msgs/Header\n"
    "uint32 seq\n"
    "time stamp\n"
    "string frame_id\n"
    "\n"
    "================================================================================\n"
    "MSG: livox_ros_driver/CustomPoint\n"
    "uint32 offset_time\n"
    "float32 x\n"
    "float32 y\n"
    "float32 z\n"
    "uint8 reflectivity\n"
    "uint8 tag\n"
    "uint8 line\n";

Ros1CloudType ros1CloudType(const Ros1Connection& c, const std::string& where) {
  if (c.type == kRos1PointCloud2) return Ros1CloudType::PointCloud2;
  if (isLivoxCustomMsg(c.type)) {
    if (c.md5sum == kLivoxCustomMsgMd5) return Ros1CloudType::LivoxCustomMsg;
    throw std::runtime_error(where + ": message type " + c.type + " with md5sum " + c.md5sum +
                             " is another definition than the one cosmo reads (md5sum " + kLivoxCustomMsgMd5 +
                             ": timebase, point_num, lidar_id, rsvd[3], points of offset_time x y z reflectivity tag "
                             "line), e.g. an older livox_ros_driver's: convert it to sensor_msgs/PointCloud2 with a "
                             "per-point time field (docs/data.md lists the ones read)");
  }
  throw std::runtime_error(where + ": message type " + c.type + " (md5sum " + c.md5sum + ") is not " +
                           kRos1PointCloud2 + " or livox_ros_driver/CustomMsg");
}

namespace {

/// A std_msgs/Header: its stamp and frame into `L` (seq is not used).
template <typename Fail>
void readHeader(ByteCursor<Fail>& in, CloudLayout& L) {
  in.template value<std::uint32_t>("header.seq");
  const auto sec = in.template value<std::uint32_t>("header.stamp.sec");
  const auto nsec = in.template value<std::uint32_t>("header.stamp.nsec");
  L.stamp = static_cast<StampNs>(sec) * 1000000000ULL + nsec;
  L.frame_id = in.string("header.frame_id");
}

}  // namespace

CloudView parseLivoxCustomMsg(const std::uint8_t* message, std::size_t size, const std::string& source) {
  ByteCursor in(message, size, LivoxFail{source, size});
  CloudView view;
  CloudLayout& L = view.layout;
  readHeader(in, L);
  L.time_base = in.value<std::uint64_t>("timebase");
  const auto point_num = in.value<std::uint32_t>("point_num");
  in.value<std::uint8_t>("lidar_id");
  in.bytes(3, "rsvd");
  const std::size_t count_at = in.offset();
  const auto count = in.value<std::uint32_t>("points");
  if (count > in.left() / kLivoxPointBytes)
    in.failAt("points",
              std::to_string(count) + " points of " + std::to_string(kLivoxPointBytes) + " bytes cannot fit in " +
                  std::to_string(in.left()) + " bytes",
              count_at);
  if (count != point_num)
    in.failAt("points", "holds " + std::to_string(count) + " points, point_num says " + std::to_string(point_num),
              count_at);
  view.bytes = static_cast<std::size_t>(count) * kLivoxPointBytes;
  view.data = in.bytes(view.bytes, "points");
  L.height = 1;
  L.width = count;
  L.fields = livoxPointFields();
  L.point_step = kLivoxPointBytes;
  L.row_step = static_cast<std::uint32_t>(view.bytes);
  L.is_dense = true;
  return view;
}

CloudView parseRos1Cloud(Ros1CloudType type, const std::uint8_t* message, std::size_t size, const std::string& source) {
  return type == Ros1CloudType::LivoxCustomMsg ? parseLivoxCustomMsg(message, size, source)
                                               : parseRos1PointCloud2(message, size, source);
}

std::vector<std::uint8_t> serializeLivoxCustomMsg(const Scan& scan, const std::string& frame_id) {
  const std::size_t n = scan.size();
  // The earliest point's time, in whole ns before the stamp; each point's offset from it rounded to the ns.
  double t_min = 0.0;
  if (scan.hasTime())
    for (float t : scan.time) t_min = std::min(t_min, static_cast<double>(t));
  const auto before = static_cast<StampNs>(std::llround(-t_min * 1e9));
  const StampNs timebase = scan.stamp > before ? scan.stamp - before : 0;
  std::vector<std::uint8_t> out;
  out.reserve(64 + frame_id.size() + n * kLivoxPointBytes);
  put(out, std::uint32_t{0});
  put(out, static_cast<std::uint32_t>(scan.stamp / 1000000000ULL));
  put(out, static_cast<std::uint32_t>(scan.stamp % 1000000000ULL));
  put(out, static_cast<std::uint32_t>(frame_id.size()));
  out.insert(out.end(), frame_id.begin(), frame_id.end());
  put(out, static_cast<std::uint64_t>(timebase));
  put(out, static_cast<std::uint32_t>(n));
  put(out, std::uint8_t{0});
  out.insert(out.end(), 3, 0);
  put(out, static_cast<std::uint32_t>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const double t = scan.hasTime() ? static_cast<double>(scan.time[i]) : 0.0;
    const double offset = std::max(0.0, (t - t_min) * 1e9);
    put(out, static_cast<std::uint32_t>(std::min(std::llround(offset), 0xffffffffLL)));
    out.insert(out.end(), reinterpret_cast<const std::uint8_t*>(scan.points[i].data()),
               reinterpret_cast<const std::uint8_t*>(scan.points[i].data()) + 12);
    const float intensity = scan.hasIntensity() ? scan.intensity[i] : 0.0f;
    out.push_back(static_cast<std::uint8_t>(std::clamp(std::lround(intensity), 0L, 255L)));
    out.push_back(0);
    out.push_back(static_cast<std::uint8_t>(scan.hasRing() ? std::min<int>(scan.ring[i], 255) : 0));
  }
  return out;
}

CloudView parseRos1PointCloud2(const std::uint8_t* message, std::size_t size, const std::string& source) {
  ByteCursor in(message, size, Ros1CloudFail{source, size});
  CloudView view;
  CloudLayout& L = view.layout;
  readHeader(in, L);
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

DecodeCounts decodeRos1Cloud(Ros1CloudType type, const std::uint8_t* message, std::size_t size, bool stamp_at_end,
                             const std::string& source, Scan& scan, CloudLayout& layout) {
  CloudView v = parseRos1Cloud(type, message, size, source);
  const DecodeCounts counts = decodeCloud(v.layout, v.data, v.bytes, stamp_at_end, source, scan);
  layout = std::move(v.layout);
  return counts;
}

}  // namespace cosmo::trials
