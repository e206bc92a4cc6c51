#include "cosmo/trials/cdr_point_cloud.hpp"

#include <stdexcept>

#include "cloud_members.hpp"
#include "cosmo/common/byte_cursor.hpp"

namespace cosmo::trials {

namespace {

constexpr std::size_t kEncapsulation = 4;

/// A malformed CDR PointCloud2, named with the member and the byte offset.
struct CdrCloudFail {
  const std::string& source;
  std::size_t size;
  [[noreturn]] void operator()(const char* what, const std::string& why, std::size_t at) const {
    throw std::runtime_error(source + ": malformed CDR PointCloud2 at " + what + " (byte " + std::to_string(at) +
                             " of " + std::to_string(size) + "): " + why);
  }
};

/// Reads CDR members in order: each value aligned to its size from the end of the encapsulation header, strings
/// with their NUL.
class CdrIn {
 public:
  CdrIn(const std::uint8_t* p, std::size_t size, const std::string& source)
      : in_(p, size, CdrCloudFail{source, size}, kEncapsulation) {}

  template <typename T>
  T value(const char* what) {
    in_.align(sizeof(T), kEncapsulation, what);
    return in_.template value<T>(what);
  }
  std::string string(const char* what) {
    const auto len = value<std::uint32_t>(what);
    if (len == 0) in_.fail(what, "string length 0 (CDR strings hold at least their NUL)");
    const std::size_t at = in_.offset();
    const char* s = reinterpret_cast<const char*>(in_.bytes(len, what));
    if (s[len - 1] != '\0') in_.failAt(what, "string is not NUL-terminated", at);
    return std::string(s, len - 1);
  }
  const std::uint8_t* bytes(std::size_t n, const char* what) { return in_.bytes(n, what); }
  [[noreturn]] void fail(const char* what, const std::string& why) const { in_.fail(what, why); }

 private:
  ByteCursor<CdrCloudFail> in_;
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

CloudView parseCdrPointCloud2(const std::uint8_t* message, std::size_t size, const std::string& source) {
  if (size < kEncapsulation)
    throw std::runtime_error(source + ": malformed CDR PointCloud2: " + std::to_string(size) +
                             " bytes, shorter than the encapsulation header");
  if (message[0] != 0x00 || message[1] != 0x01)
    throw std::runtime_error(source + ": CDR encapsulation " + std::to_string(message[0]) + " " +
                             std::to_string(message[1]) + " is not little-endian CDR (0 1)");
  CdrIn in(message, size, source);
  CloudView view;
  CloudLayout& L = view.layout;
  const auto sec = in.value<std::int32_t>("header.stamp.sec");
  const auto nanosec = in.value<std::uint32_t>("header.stamp.nanosec");
  if (sec < 0 || nanosec >= 1000000000u) in.fail("header.stamp", "invalid stamp");
  L.stamp = static_cast<StampNs>(sec) * 1000000000ULL + nanosec;
  L.frame_id = in.string("header.frame_id");
  readCloudMembers(in, view, [&](std::uint32_t nfields) {
    if (nfields > (size - kEncapsulation) / 13) in.fail("fields", std::to_string(nfields) + " fields cannot fit");
  });
  return view;
}

DecodeCounts decodeCdrPointCloud2(const std::uint8_t* message, std::size_t size, bool stamp_at_end,
                                  const std::string& source, Scan& scan) {
  const CloudView v = parseCdrPointCloud2(message, size, source);
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
