#include "cosmo/trials/ros1_point_cloud.hpp"

#include <cstring>
#include <stdexcept>

namespace cosmo::trials {

namespace {

/// Reads little-endian values in order, checking every read against the end of the buffer.
class Ros1Reader {
 public:
  Ros1Reader(const std::uint8_t* p, std::size_t size, const std::string& source)
      : p_(p), size_(size), source_(source) {}

  template <typename T>
  T value(const char* what) {
    T v;
    std::memcpy(&v, bytes(sizeof(T), what), sizeof(T));
    return v;
  }
  std::string string(const char* what) {
    const auto len = value<std::uint32_t>(what);
    const char* s = reinterpret_cast<const char*>(bytes(len, what));
    return std::string(s, len);
  }
  const std::uint8_t* bytes(std::size_t n, const char* what) {
    if (n > size_ - pos_)
      fail(what, "truncated (needs " + std::to_string(n) + " bytes, " + std::to_string(size_ - pos_) + " left)");
    const std::uint8_t* b = p_ + pos_;
    pos_ += n;
    return b;
  }
  std::size_t left() const { return size_ - pos_; }
  [[noreturn]] void fail(const char* what, const std::string& why) const {
    throw std::runtime_error(source_ + ": malformed PointCloud2 at " + what + " (byte " + std::to_string(pos_) +
                             " of " + std::to_string(size_) + "): " + why);
  }

 private:
  const std::uint8_t* p_;
  std::size_t size_;
  const std::string& source_;
  std::size_t pos_ = 0;
};

constexpr std::size_t kFieldMinBytes = 4 + 4 + 1 + 4;  ///< empty name, offset, datatype, count

}  // namespace

Ros1CloudView parseRos1PointCloud2(const std::uint8_t* message, std::size_t size, const std::string& source) {
  Ros1Reader in(message, size, source);
  Ros1CloudView view;
  CloudLayout& L = view.layout;
  in.value<std::uint32_t>("header.seq");
  const auto sec = in.value<std::uint32_t>("header.stamp.sec");
  const auto nsec = in.value<std::uint32_t>("header.stamp.nsec");
  L.stamp = static_cast<StampNs>(sec) * 1000000000ULL + nsec;
  L.frame_id = in.string("header.frame_id");
  L.height = in.value<std::uint32_t>("height");
  L.width = in.value<std::uint32_t>("width");
  const auto nfields = in.value<std::uint32_t>("fields");
  if (nfields > in.left() / kFieldMinBytes)
    in.fail("fields", std::to_string(nfields) + " fields cannot fit in " + std::to_string(in.left()) + " bytes");
  L.fields.resize(nfields);
  for (auto& f : L.fields) {
    f.name = in.string("fields[].name");
    f.offset = in.value<std::uint32_t>("fields[].offset");
    f.datatype = in.value<std::uint8_t>("fields[].datatype");
    f.count = in.value<std::uint32_t>("fields[].count");
  }
  L.is_bigendian = in.value<std::uint8_t>("is_bigendian") != 0;
  L.point_step = in.value<std::uint32_t>("point_step");
  L.row_step = in.value<std::uint32_t>("row_step");
  view.bytes = in.value<std::uint32_t>("data");
  view.data = in.bytes(view.bytes, "data");
  L.is_dense = in.value<std::uint8_t>("is_dense") != 0;
  return view;
}

DecodeCounts decodeRos1PointCloud2(const std::uint8_t* message, std::size_t size, bool stamp_at_end,
                                   const std::string& source, Scan& scan, CloudLayout& layout) {
  Ros1CloudView v = parseRos1PointCloud2(message, size, source);
  const DecodeCounts counts = decodeCloud(v.layout, v.data, v.bytes, stamp_at_end, source, scan);
  layout = std::move(v.layout);
  return counts;
}

}  // namespace cosmo::trials
