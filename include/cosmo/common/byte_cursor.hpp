#pragma once
// Reading a serialized message's fields in order from a buffer of bytes: every read checked against the buffer's
// end, values little-endian as ROS 1 and CDR write them (x86 / ARM hosts). One cursor for the ROS 1 and CDR
// PointCloud2 decoders and the Nebula PoseGraph decoder; each says what is malformed in its own words through `Fail`.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>

namespace cosmo {

/// Little-endian uint32 at `p` (the caller checked the bounds).
inline std::uint32_t le32(const std::uint8_t* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

/// `Fail`: callable as fail(what, why, at) and throwing (`what`: the field read; `at`: the byte offset the read
/// began at). A read past the end fails with "<ends> (needs N bytes, M left)".
template <typename Fail>
class ByteCursor {
 public:
  /// Reads `data[start, size)`; `ends`: how the decoder words a read past the end.
  ByteCursor(const std::uint8_t* data, std::size_t size, Fail fail, std::size_t start = 0,
             const char* ends = "truncated")
      : data_(data), size_(size), pos_(start), ends_(ends), fail_(std::move(fail)) {}

  template <typename T>
  T value(const char* what) {
    static_assert(std::is_arithmetic_v<T>);
    T v;
    std::memcpy(&v, bytes(sizeof(T), what), sizeof(T));
    return v;
  }
  /// `n` bytes, in place.
  const std::uint8_t* bytes(std::size_t n, const char* what) {
    if (n > size_ - pos_)
      fail(what,
           std::string(ends_) + " (needs " + std::to_string(n) + " bytes, " + std::to_string(size_ - pos_) + " left)");
    const std::uint8_t* b = data_ + pos_;
    pos_ += n;
    return b;
  }
  /// A uint32 length, then that many bytes, as a string.
  std::string string(const char* what) {
    const auto len = value<std::uint32_t>(what);
    return std::string(reinterpret_cast<const char*>(bytes(len, what)), len);
  }
  /// Skips to the next multiple of `alignment` counted from byte `origin` (CDR: the end of its encapsulation).
  void align(std::size_t alignment, std::size_t origin, const char* what) {
    pos_ += (alignment - (pos_ - origin) % alignment) % alignment;
    if (pos_ > size_) fail(what, "truncated");
  }

  std::size_t offset() const { return pos_; }
  std::size_t size() const { return size_; }
  std::size_t left() const { return size_ - pos_; }

  [[noreturn]] void fail(const char* what, const std::string& why) const { failAt(what, why, pos_); }
  [[noreturn]] void failAt(const char* what, const std::string& why, std::size_t at) const {
    fail_(what, why, at);
    std::abort();  // unreachable: `Fail` throws
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_, pos_;
  const char* ends_;
  Fail fail_;
};

}  // namespace cosmo
