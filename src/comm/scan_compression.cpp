#include "cosmo/comm/scan_compression.hpp"

#include <lzma.h>

#include <cstring>
#include <stdexcept>

namespace cosmo::comm {

namespace {
static_assert(sizeof(float) == 4, "float32 payload");

bool littleEndian() {
  const std::uint16_t one = 1;
  std::uint8_t b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

void putFloat(std::uint8_t* dst, float v) {
  std::uint32_t u;
  std::memcpy(&u, &v, 4);
  for (int i = 0; i < 4; ++i) dst[i] = static_cast<std::uint8_t>(u >> (8 * i));
}

float getFloat(const std::uint8_t* src) {
  std::uint32_t u = 0;
  for (int i = 0; i < 4; ++i) u |= static_cast<std::uint32_t>(src[i]) << (8 * i);
  float v;
  std::memcpy(&v, &u, 4);
  return v;
}
}  // namespace

std::vector<std::uint8_t> compressScan(const Scan& scan, std::uint32_t preset) {
  std::vector<std::uint8_t> raw(rawPayloadBytes(scan));
  if (littleEndian()) {
    for (std::size_t i = 0; i < scan.size(); ++i) std::memcpy(&raw[12 * i], scan.points[i].data(), 12);
  } else {
    for (std::size_t i = 0; i < scan.size(); ++i)
      for (int k = 0; k < 3; ++k) putFloat(&raw[12 * i + 4 * k], scan.points[i][k]);
  }
  std::vector<std::uint8_t> out(lzma_stream_buffer_bound(raw.size()));
  std::size_t out_pos = 0;
  const lzma_ret ret = lzma_easy_buffer_encode(preset, LZMA_CHECK_CRC64, nullptr, raw.data(), raw.size(), out.data(),
                                               &out_pos, out.size());
  if (ret != LZMA_OK)
    throw std::runtime_error("compressScan: liblzma encoder failed (code " + std::to_string(ret) + ")");
  out.resize(out_pos);
  return out;
}

Scan decompressScan(const std::vector<std::uint8_t>& bytes) {
  lzma_stream strm = LZMA_STREAM_INIT;
  if (lzma_stream_decoder(&strm, UINT64_MAX, LZMA_CONCATENATED) != LZMA_OK)
    throw std::runtime_error("decompressScan: cannot initialize the liblzma decoder");
  std::vector<std::uint8_t> raw(std::max<std::size_t>(4096, bytes.size() * 4));
  strm.next_in = bytes.data();
  strm.avail_in = bytes.size();
  strm.next_out = raw.data();
  strm.avail_out = raw.size();
  lzma_action action = LZMA_RUN;
  lzma_ret ret = LZMA_OK;
  while (true) {
    if (strm.avail_in == 0) action = LZMA_FINISH;
    ret = lzma_code(&strm, action);
    if (ret == LZMA_STREAM_END) break;
    if (ret != LZMA_OK) {
      lzma_end(&strm);
      throw std::runtime_error("decompressScan: payload is not a valid xz stream (liblzma code " + std::to_string(ret) +
                               ")");
    }
    if (strm.avail_out == 0) {
      const std::size_t used = raw.size();
      raw.resize(used * 2);
      strm.next_out = raw.data() + used;
      strm.avail_out = raw.size() - used;
    }
  }
  const std::size_t n = strm.total_out;
  lzma_end(&strm);
  if (n % 12 != 0)
    throw std::runtime_error("decompressScan: payload of " + std::to_string(n) +
                             " bytes is not a whole number of [x y z] float32 points");
  Scan scan;
  scan.points.resize(n / 12);
  for (std::size_t i = 0; i < scan.points.size(); ++i)
    for (int k = 0; k < 3; ++k) scan.points[i][k] = getFloat(&raw[12 * i + 4 * k]);
  return scan;
}

}  // namespace cosmo::comm
