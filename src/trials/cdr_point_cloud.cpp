#include "cosmo/trials/cdr_point_cloud.hpp"

#include <cstring>
#include <stdexcept>

namespace cosmo::trials {

namespace {

constexpr std::size_t kEncapsulation = 4;

/// Reads little-endian CDR values in order, checking every read against the end of the buffer.
class CdrReader {
 public:
  CdrReader(const std::uint8_t* p, std::size_t size, const std::string& source) : p_(p), size_(size), source_(source) {}

  template <typename T>
  T value(const char* what) {
    align(sizeof(T), what);
    need(sizeof(T), what);
    T v;
    std::memcpy(&v, p_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  std::string string(const char* what) {
    const auto len = value<std::uint32_t>(what);
    if (len == 0) fail(what, "string length 0 (CDR strings hold at least their NUL)");
    need(len, what);
    const char* s = reinterpret_cast<const char*>(p_ + pos_);
    if (s[len - 1] != '\0') fail(what, "string is not NUL-terminated");
    pos_ += len;
    return std::string(s, len - 1);
  }
  const std::uint8_t* bytes(std::size_t n, const char* what) {
    need(n, what);
    const std::uint8_t* b = p_ + pos_;
    pos_ += n;
    return b;
  }
  [[noreturn]] void fail(const char* what, const std::string& why) const {
    throw std::runtime_error(source_ + ": malformed CDR PointCloud2 at " + what + " (byte " + std::to_string(pos_) +
                             " of " + std::to_string(size_) + "): " + why);
  }

 private:
  void align(std::size_t a, const char* what) {
    const std::size_t rel = pos_ - kEncapsulation;
    pos_ += (a - rel % a) % a;
    if (pos_ > size_) fail(what, "truncated");
  }
  void need(std::size_t n, const char* what) const {
    if (n > size_ - pos_)
      fail(what, "truncated (needs " + std::to_string(n) + " bytes, " + std::to_string(size_ - pos_) + " left)");
  }

  const std::uint8_t* p_;
  std::size_t size_;
  const std::string& source_;
  std::size_t pos_ = kEncapsulation;
};

/// Appends little-endian CDR values with the same alignment rule.
class CdrWriter {
 public:
  CdrWriter() : out_{0x00, 0x01, 0x00, 0x00} {}
  template <typename T>
  void value(T v) {
    align(sizeof(T));
    const auto* b = reinterpret_cast<const std::uint8_t*>(&v);
    out_.insert(out_.end(), b, b + sizeof(T));
  }
  void string(const std::string& s) {
    value(static_cast<std::uint32_t>(s.size() + 1));
    out_.insert(out_.end(), s.begin(), s.end());
    out_.push_back(0);
  }
  void bytes(const std::vector<std::uint8_t>& b) {
    value(static_cast<std::uint32_t>(b.size()));
    out_.insert(out_.end(), b.begin(), b.end());
  }
  std::vector<std::uint8_t> take() { return std::move(out_); }

 private:
  void align(std::size_t a) {
    while ((out_.size() - kEncapsulation) % a) out_.push_back(0);
  }
  std::vector<std::uint8_t> out_;
};

}  // namespace

CdrCloudView parseCdrPointCloud2(const std::uint8_t* message, std::size_t size, const std::string& source) {
  if (size < kEncapsulation)
    throw std::runtime_error(source + ": malformed CDR PointCloud2: " + std::to_string(size) +
                             " bytes, shorter than the encapsulation header");
  if (message[0] != 0x00 || message[1] != 0x01)
    throw std::runtime_error(source + ": CDR encapsulation " + std::to_string(message[0]) + " " +
                             std::to_string(message[1]) + " is not little-endian CDR (0 1)");
  CdrReader in(message, size, source);
  CdrCloudView view;
  CloudLayout& L = view.layout;
  const auto sec = in.value<std::int32_t>("header.stamp.sec");
  const auto nanosec = in.value<std::uint32_t>("header.stamp.nanosec");
  if (sec < 0 || nanosec >= 1000000000u) in.fail("header.stamp", "invalid stamp");
  L.stamp = static_cast<StampNs>(sec) * 1000000000ULL + nanosec;
  L.frame_id = in.string("header.frame_id");
  L.height = in.value<std::uint32_t>("height");
  L.width = in.value<std::uint32_t>("width");
  const auto nfields = in.value<std::uint32_t>("fields");
  if (nfields > (size - kEncapsulation) / 13) in.fail("fields", std::to_string(nfields) + " fields cannot fit");
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

DecodeCounts decodeCdrPointCloud2(const std::uint8_t* message, std::size_t size, bool stamp_at_end,
                                  const std::string& source, Scan& scan) {
  const CdrCloudView v = parseCdrPointCloud2(message, size, source);
  return decodeCloud(v.layout, v.data, v.bytes, stamp_at_end, source, scan);
}

std::vector<std::uint8_t> encodeCdrPointCloud2(const RawCloud& cloud) {
  const CloudLayout& L = cloud.layout;
  CdrWriter out;
  out.value(static_cast<std::int32_t>(L.stamp / 1000000000ULL));
  out.value(static_cast<std::uint32_t>(L.stamp % 1000000000ULL));
  out.string(L.frame_id);
  out.value(L.height);
  out.value(L.width);
  out.value(static_cast<std::uint32_t>(L.fields.size()));
  for (const auto& f : L.fields) {
    out.string(f.name);
    out.value(f.offset);
    out.value(f.datatype);
    out.value(f.count);
  }
  out.value(static_cast<std::uint8_t>(L.is_bigendian));
  out.value(L.point_step);
  out.value(L.row_step);
  out.bytes(cloud.data);
  out.value(static_cast<std::uint8_t>(L.is_dense));
  return out.take();
}

}  // namespace cosmo::trials
