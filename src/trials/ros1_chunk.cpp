#include "ros1_chunk.hpp"

#include <bzlib.h>
#include <lz4frame.h>

#include <algorithm>
#include <memory>
#include <string>

namespace cosmo::trials::ros1 {

namespace {

/// The first output size tried: all of it for usual chunks (bz2 and lz4 shrink point clouds 1.5-4 times), else it
/// doubles as the stream fills it.
std::size_t firstOutput(std::size_t stored, std::uint32_t size) {
  return std::min<std::size_t>(size, 32 * stored + (64u << 10));
}

/// Makes `out` hold at least `limit` bytes.
void reserveOutput(std::vector<std::uint8_t>& out, std::size_t limit) {
  if (out.size() < limit) out.resize(limit);
}

[[noreturn]] void sizeMismatch(const Place& place, std::size_t produced, std::uint32_t size, const char* codec) {
  fail(place, "chunk",
       std::string(codec) + " data decompresses to " + (produced > size ? "more than " : "") +
           std::to_string(std::min<std::size_t>(produced, size)) + " bytes, the chunk's field 'size' says " +
           std::to_string(size));
}

[[noreturn]] void truncated(const Place& place, const char* codec) {
  fail(place, "chunk", std::string(codec) + " data ends before its stream does (truncated)");
}

void bz2(const std::uint8_t* in, std::size_t n, std::uint32_t size, std::vector<std::uint8_t>& out,
         const Place& place) {
  bz_stream s{};
  if (BZ2_bzDecompressInit(&s, 0, 0) != BZ_OK) fail(place, "chunk", "cannot start bz2 decompression");
  std::unique_ptr<bz_stream, int (*)(bz_stream*)> end(&s, BZ2_bzDecompressEnd);
  s.next_in = const_cast<char*>(reinterpret_cast<const char*>(in));
  s.avail_in = static_cast<unsigned>(n);
  std::size_t produced = 0, limit = firstOutput(n, size);
  reserveOutput(out, limit);
  for (;;) {
    s.next_out = reinterpret_cast<char*>(out.data() + produced);
    s.avail_out = static_cast<unsigned>(limit - produced);
    const int rc = BZ2_bzDecompress(&s);
    produced = limit - s.avail_out;
    if (rc == BZ_STREAM_END) break;
    if (rc != BZ_OK) fail(place, "chunk", "bz2 data is damaged (libbz2 error " + std::to_string(rc) + ")");
    if (s.avail_out > 0) truncated(place, "bz2");  // the input ran out first
    if (limit == size) {                             // full at the header's size: the stream must end here
      char extra;
      s.next_out = &extra;
      s.avail_out = 1;
      const int more = BZ2_bzDecompress(&s);
      if (more == BZ_STREAM_END && s.avail_out == 1) break;
      if (more == BZ_OK && s.avail_out == 1) truncated(place, "bz2");
      if (more == BZ_OK || more == BZ_STREAM_END) sizeMismatch(place, produced + 1, size, "bz2");
      fail(place, "chunk", "bz2 data is damaged (libbz2 error " + std::to_string(more) + ")");
    }
    limit = std::min<std::size_t>(size, 2 * limit);
    reserveOutput(out, limit);
  }
  if (produced != size) sizeMismatch(place, produced, size, "bz2");
  out.resize(produced);
}

void lz4(const std::uint8_t* in, std::size_t n, std::uint32_t size, std::vector<std::uint8_t>& out,
         const Place& place) {
  LZ4F_dctx* ctx = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&ctx, LZ4F_VERSION)))
    fail(place, "chunk", "cannot start lz4 decompression");
  std::unique_ptr<LZ4F_dctx, LZ4F_errorCode_t (*)(LZ4F_dctx*)> end(ctx, LZ4F_freeDecompressionContext);
  std::size_t consumed = 0, produced = 0, limit = firstOutput(n, size);
  reserveOutput(out, limit);
  for (;;) {
    std::uint8_t extra[64];  // past the header's size: anything decoded there is too much
    const bool full = produced == limit;
    const std::size_t room = full ? sizeof extra : limit - produced;
    std::size_t wrote = room, src = n - consumed;
    const std::size_t hint =
        LZ4F_decompress(ctx, full ? extra : out.data() + produced, &wrote, in + consumed, &src, nullptr);
    if (LZ4F_isError(hint))
      fail(place, "chunk", std::string("lz4 data is damaged (") + LZ4F_getErrorName(hint) + ")");
    consumed += src;
    if (full && wrote > 0) sizeMismatch(place, produced + wrote, size, "lz4");
    if (!full) produced += wrote;
    if (hint == 0) break;  // the frame is complete, its checksum verified
    if (wrote < room && consumed == n) truncated(place, "lz4");
    if (produced == limit && limit < size) {
      limit = std::min<std::size_t>(size, 2 * limit);
      reserveOutput(out, limit);
    }
  }
  if (produced != size) sizeMismatch(place, produced, size, "lz4");
  out.resize(produced);
}

}  // namespace

void decompressChunk(Ros1Compression compression, const std::uint8_t* in, std::size_t n, std::uint32_t size,
                     std::vector<std::uint8_t>& out, const Place& place) {
  if (compression == Ros1Compression::Bz2) return bz2(in, n, size, out, place);
  if (compression == Ros1Compression::Lz4) return lz4(in, n, size, out, place);
  out.assign(in, in + n);
}

}  // namespace cosmo::trials::ros1
