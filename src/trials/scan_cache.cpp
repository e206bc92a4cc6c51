#include "cosmo/trials/scan_cache.hpp"

#include <lz4.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <stdexcept>
#include <tuple>

#include "cosmo/common/byte_cursor.hpp"

namespace fs = std::filesystem;

namespace cosmo::trials {

namespace {

constexpr char kMagic[10] = {'C', 'O', 'S', 'M', 'O', 'S', 'C', 'A', 'N', 'S'};
constexpr std::streamoff kCountOffset = sizeof(kMagic) + sizeof(std::uint32_t);
constexpr std::size_t kRecordHead = sizeof(std::uint32_t) + sizeof(std::uint64_t);  ///< body length, its hash

template <typename T>
void put(std::ofstream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof v);
}
template <typename T>
void append(std::vector<char>& buf, const T& v) {
  const auto* p = reinterpret_cast<const char*>(&v);
  buf.insert(buf.end(), p, p + sizeof v);
}
void appendBytes(std::vector<char>& buf, const void* data, std::size_t n) {
  const auto* p = static_cast<const char*>(data);
  buf.insert(buf.end(), p, p + n);
}

/// Unique per process and per writer (two trials of one run may share a bag).
std::string temporaryName(const std::string& path) {
  static std::atomic<unsigned> writers{0};
  return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(writers++);
}

/// Byte planes: byte k of every element together (W: the element's width; xyz points are one 12-byte element, so
/// their planes are also split by axis). Floats of neighbouring points share sign, exponent and high mantissa
/// bytes, which LZ4 then finds as runs.
template <std::size_t W>
void toPlanes(const char* src, std::size_t n, char* dst) {
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < W; ++k) dst[k * n + i] = src[i * W + k];
}
template <std::size_t W>
void fromPlanes(const char* src, std::size_t n, char* dst) {
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < W; ++k) dst[i * W + k] = src[k * n + i];
}

std::size_t arrayBytes(std::size_t n, std::uint8_t flags) {
  return n * (12 + ((flags & 1) ? 4 : 0) + ((flags & 2) ? 4 : 0) + ((flags & 4) ? 2 : 0));
}

/// The bag's content identity, once per process per (file, size, modification time).
std::uint64_t bagIdentity(const std::string& bag_path) {
  static std::mutex mutex;
  static std::map<std::tuple<std::string, std::uint64_t, long long>, std::uint64_t> known;
  const fs::path bag = fs::weakly_canonical(fs::absolute(bag_path));
  const auto key = std::make_tuple(bag.string(), static_cast<std::uint64_t>(fs::file_size(bag)),
                                   static_cast<long long>(fs::last_write_time(bag).time_since_epoch().count()));
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (auto it = known.find(key); it != known.end()) return it->second;
  }
  const std::uint64_t id = cache::fileIdentity(bag);
  std::lock_guard<std::mutex> lock(mutex);
  known[key] = id;
  return id;
}

std::string keyedPath(const std::string& dir, const std::string& bag_path, const std::string& topic, bool stamp_at_end,
                      const char* extension) {
  const std::string bare_topic = !topic.empty() && topic[0] == '/' ? topic.substr(1) : topic;
  char id[17];
  std::snprintf(id, sizeof id, "%016llx", static_cast<unsigned long long>(bagIdentity(bag_path)));
  const std::string key = std::string(id) + "\n" + bare_topic + "\n" + (stamp_at_end ? "end" : "start") + "\n" +
                          std::to_string(kScanCacheVersion);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(cache::hashBytes(key.data(), key.size())));
  return (fs::path(dir) / (std::string(hex) + extension)).string();
}

}  // namespace

ScanCompression scanCacheCompression() {
  const char* v = std::getenv("COSMO_SCAN_CACHE_COMPRESSION");
  if (!v || std::string(v) == "lz4") return ScanCompression::Lz4;
  if (std::string(v) == "none") return ScanCompression::None;
  throw std::invalid_argument(std::string("COSMO_SCAN_CACHE_COMPRESSION: expected lz4 or none, got '") + v + "'");
}

std::string scanCacheDir() { return cache::cacheRoot(cache::Kind::Scan).string(); }

std::string scanCachePath(const std::string& dir, const std::string& bag_path, const std::string& topic,
                          bool stamp_at_end) {
  return keyedPath(dir, bag_path, topic, stamp_at_end, ".scans");
}

std::string scanSpanPath(const std::string& dir, const std::string& bag_path, const std::string& topic,
                         bool stamp_at_end) {
  return keyedPath(dir, bag_path, topic, stamp_at_end, ".span");
}

bool readCachedSpan(const std::string& path, StampNs& first, StampNs& last) {
  std::ifstream in(path);
  std::string magic;
  unsigned long long a = 0, b = 0;
  if (!(in >> magic >> a >> b) || magic != "cosmo-span-1" || b < a) return false;
  first = static_cast<StampNs>(a);
  last = static_cast<StampNs>(b);
  return true;
}

void writeCachedSpan(const std::string& path, StampNs first, StampNs last) {
  std::error_code ec;
  fs::create_directories(fs::path(path).parent_path(), ec);
  const std::string tmp = temporaryName(path);
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << "cosmo-span-1 " << static_cast<unsigned long long>(first) << " " << static_cast<unsigned long long>(last)
        << "\n";
    if (!out) {
      fs::remove(tmp, ec);
      return;  // a cache that cannot be written is only not there next time
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) fs::remove(tmp, ec);
}

std::uint64_t CachedScanSource::bytesLeft() {
  const auto at = in_.tellg();
  return at < 0 || static_cast<std::uint64_t>(at) > file_size_ ? 0 : file_size_ - static_cast<std::uint64_t>(at);
}

void CachedScanSource::damaged(const std::string& why) const {
  throw std::runtime_error(path_ + ": scan cache damaged at scan " + std::to_string(read_) + " (" + why + ")");
}

CachedScanSource::CachedScanSource(const std::string& path)
    : path_(path), in_(path, std::ios::binary), hold_(std::make_unique<cache::EntryUse>(path)) {
  std::error_code ec;
  file_size_ = fs::file_size(path, ec);
  if (ec) file_size_ = 0;
  char magic[sizeof kMagic] = {};
  std::uint32_t version = 0;
  std::uint64_t count = 0;
  std::uint8_t compression = 0;
  in_.read(magic, sizeof magic);
  in_.read(reinterpret_cast<char*>(&version), sizeof version);
  in_.read(reinterpret_cast<char*>(&count), sizeof count);
  in_.read(reinterpret_cast<char*>(&compression), sizeof compression);
  if (!in_ || std::memcmp(magic, kMagic, sizeof kMagic) != 0 || version != kScanCacheVersion ||
      compression > static_cast<std::uint8_t>(ScanCompression::Lz4))
    throw std::runtime_error(path + ": not a scan cache of version " + std::to_string(kScanCacheVersion));
  // Every scan's record holds at least its head: a count the file cannot hold is damage.
  if (count > bytesLeft() / kRecordHead) damaged(std::to_string(count) + " scans announced in a shorter file");
  size_ = static_cast<std::size_t>(count);
  compression_ = static_cast<ScanCompression>(compression);
}

CachedScanSource::~CachedScanSource() = default;

bool CachedScanSource::next(Scan& scan) {
  if (read_ >= size_) return false;
  std::uint32_t length = 0;
  std::uint64_t hash = 0;
  in_.read(reinterpret_cast<char*>(&length), sizeof length);
  in_.read(reinterpret_cast<char*>(&hash), sizeof hash);
  if (!in_) damaged("truncated");
  if (length > bytesLeft()) damaged("a record of " + std::to_string(length) + " bytes past the end of the file");
  record_.resize(length);
  in_.read(record_.data(), length);
  if (!in_) damaged("truncated");
  if (cache::hashBytes(record_.data(), length) != hash) damaged("its bytes do not match their hash");

  auto fail = [this](const char* what, const std::string& why, std::size_t) {
    damaged(std::string(what) + ": " + why);
  };
  ByteCursor<decltype(fail)> c(reinterpret_cast<const std::uint8_t*>(record_.data()), length, fail);
  const auto stamp = c.value<std::uint64_t>("stamp");
  const auto n = c.value<std::uint32_t>("point count");
  const auto flags = c.value<std::uint8_t>("fields present");
  const auto points = c.value<std::uint64_t>("decoded points");
  const auto invalid = c.value<std::uint64_t>("invalid points");
  layout_.height = c.value<std::uint32_t>("height");
  layout_.width = c.value<std::uint32_t>("width");
  layout_.point_step = c.value<std::uint32_t>("point step");
  const auto nfields = c.value<std::uint32_t>("field count");
  if (nfields > c.left() / 13) damaged("field count " + std::to_string(nfields));
  layout_.fields.resize(nfields);
  for (auto& f : layout_.fields) {
    f.name = c.string("field name");
    f.offset = c.value<std::uint32_t>("field offset");
    f.datatype = c.value<std::uint8_t>("field type");
    f.count = c.value<std::uint32_t>("field count");
  }
  const std::size_t raw = arrayBytes(n, flags);
  const char* payload = reinterpret_cast<const char*>(record_.data()) + c.offset();
  const char* arrays = payload;
  if (compression_ == ScanCompression::None) {
    if (c.left() != raw)
      damaged(std::to_string(c.left()) + " bytes of points where " + std::to_string(n) + " need " +
              std::to_string(raw));
  } else {
    if (raw > static_cast<std::size_t>(LZ4_MAX_INPUT_SIZE)) damaged(std::to_string(n) + " points");
    raw_.resize(raw);
    const int got = LZ4_decompress_safe(payload, raw_.data(), static_cast<int>(c.left()), static_cast<int>(raw));
    if (got != static_cast<int>(raw)) damaged("the compressed points do not decompress");
    arrays = raw_.data();
  }
  auto take = [&](auto& v, bool present, auto planes) {
    v.resize(present ? n : 0);
    if (!present) return;
    const std::size_t bytes = static_cast<std::size_t>(n) * sizeof(v[0]);
    if (compression_ == ScanCompression::None)
      std::memcpy(v.data(), arrays, bytes);
    else
      planes(arrays, n, reinterpret_cast<char*>(v.data()));
    arrays += bytes;
  };
  take(scan.points, true, fromPlanes<12>);
  take(scan.intensity, flags & 1, fromPlanes<4>);
  take(scan.time, flags & 2, fromPlanes<4>);
  take(scan.ring, flags & 4, fromPlanes<2>);
  scan.stamp = stamp;
  counts_ = {static_cast<std::size_t>(points), static_cast<std::size_t>(invalid)};
  layout_.stamp = stamp;
  ++read_;
  return true;
}

CachingScanSource::CachingScanSource(std::unique_ptr<TrialScanSource> source, const std::string& path,
                                     const std::string& info, ScanCompression compression)
    : source_(std::move(source)), path_(path), tmp_(temporaryName(path)), info_(info), compression_(compression) {
  cache::maxSize(cache::Kind::Scan);  // a bad limit is an error now, not after the whole trial
  fs::create_directories(fs::path(path).parent_path());
  out_.open(tmp_, std::ios::binary | std::ios::trunc);
  if (!out_) throw std::runtime_error(tmp_ + ": cannot write the scan cache");
  out_.write(kMagic, sizeof kMagic);
  put(out_, kScanCacheVersion);
  put(out_, std::uint64_t{0});  // the count, written when complete
  put(out_, static_cast<std::uint8_t>(compression_));
}

CachingScanSource::~CachingScanSource() {
  if (done_) return;
  out_.close();
  std::error_code ec;
  fs::remove(tmp_, ec);  // not read to its end: no cache
}

void CachingScanSource::finish() {
  done_ = true;
  out_.seekp(kCountOffset);
  put(out_, static_cast<std::uint64_t>(written_));
  const bool ok = static_cast<bool>(out_);
  out_.close();
  std::error_code ec;
  if (ok && !out_.fail()) fs::rename(tmp_, path_, ec);
  if (!ok || out_.fail() || ec) {
    fs::remove(tmp_, ec);  // a failed write (disk full) leaves no cache
    return;
  }
  if (!info_.empty()) cache::writeInfo(cache::infoPathOf(path_), info_);
  try {
    cache::applyLimit(cache::Kind::Scan, fs::path(path_).parent_path(), fs::path(path_).stem().string());
  } catch (const std::exception& e) {
    std::cerr << "cosmo cache (scan): " << e.what() << "\n";  // the scans are read; only the limit was not applied
  }
}

bool CachingScanSource::next(Scan& scan) {
  if (!source_->next(scan)) {
    if (!done_) finish();
    return false;
  }
  const DecodeCounts c = source_->lastCounts();
  const CloudLayout& L = source_->lastLayout();
  const auto flags =
      static_cast<std::uint8_t>((scan.hasIntensity() ? 1 : 0) | (scan.hasTime() ? 2 : 0) | (scan.hasRing() ? 4 : 0));
  const std::size_t n = scan.size();
  record_.clear();
  append(record_, static_cast<std::uint64_t>(scan.stamp));
  append(record_, static_cast<std::uint32_t>(n));
  append(record_, flags);
  append(record_, static_cast<std::uint64_t>(c.points));
  append(record_, static_cast<std::uint64_t>(c.invalid));
  append(record_, L.height);
  append(record_, L.width);
  append(record_, L.point_step);
  append(record_, static_cast<std::uint32_t>(L.fields.size()));
  for (const auto& f : L.fields) {
    append(record_, static_cast<std::uint32_t>(f.name.size()));
    appendBytes(record_, f.name.data(), f.name.size());
    append(record_, f.offset);
    append(record_, f.datatype);
    append(record_, f.count);
  }
  const std::size_t raw = arrayBytes(n, flags);
  if (compression_ == ScanCompression::None) {
    appendBytes(record_, scan.points.data(), n * 12);
    if (flags & 1) appendBytes(record_, scan.intensity.data(), n * 4);
    if (flags & 2) appendBytes(record_, scan.time.data(), n * 4);
    if (flags & 4) appendBytes(record_, scan.ring.data(), n * 2);
  } else {
    raw_.resize(raw);
    char* at = raw_.data();
    toPlanes<12>(reinterpret_cast<const char*>(scan.points.data()), n, at), at += n * 12;
    if (flags & 1) toPlanes<4>(reinterpret_cast<const char*>(scan.intensity.data()), n, at), at += n * 4;
    if (flags & 2) toPlanes<4>(reinterpret_cast<const char*>(scan.time.data()), n, at), at += n * 4;
    if (flags & 4) toPlanes<2>(reinterpret_cast<const char*>(scan.ring.data()), n, at), at += n * 2;
    const std::size_t head = record_.size();
    record_.resize(head + static_cast<std::size_t>(LZ4_compressBound(static_cast<int>(raw))));
    const int packed = LZ4_compress_default(raw_.data(), record_.data() + head, static_cast<int>(raw),
                                            static_cast<int>(record_.size() - head));
    if (packed <= 0) throw std::runtime_error(tmp_ + ": LZ4 failed on scan " + std::to_string(written_));
    record_.resize(head + static_cast<std::size_t>(packed));
  }
  if (record_.size() > 0xffffffffULL) throw std::runtime_error(tmp_ + ": a scan too large for the scan cache");
  put(out_, static_cast<std::uint32_t>(record_.size()));
  put(out_, cache::hashBytes(record_.data(), record_.size()));
  out_.write(record_.data(), static_cast<std::streamsize>(record_.size()));
  ++written_;
  return true;
}

namespace {

void removeDamaged(const std::string& path, const std::string& why) {
  std::cerr << "cosmo: warning: " << why << "; removed it, the bag is decoded again (and the cache rebuilt when the "
            << "trial is read to its end)\n";
  std::error_code ec;
  fs::remove(path, ec);
}

/// A cached source that, when the cache turns out damaged, goes on with the decode from the same scan.
class RecoveringScanSource : public TrialScanSource {
 public:
  RecoveringScanSource(std::unique_ptr<CachedScanSource> cached, std::string path,
                       std::function<std::unique_ptr<TrialScanSource>()> decode, std::string info)
      : cached_(std::move(cached)), path_(std::move(path)), decode_(std::move(decode)), info_(std::move(info)) {}
  bool next(Scan& scan) override {
    if (cached_) {
      try {
        if (!cached_->next(scan)) return false;
        ++read_;
        return true;
      } catch (const std::runtime_error& e) {
        cached_.reset();
        removeDamaged(path_, e.what());
        decoded_ = std::make_unique<CachingScanSource>(decode_(), path_, info_);
        for (std::size_t k = 0; k < read_; ++k)
          if (!decoded_->next(scan)) return false;
      }
    }
    return decoded_->next(scan);
  }
  std::size_t size() const override { return cached_ ? cached_->size() : decoded_->size(); }
  const CloudLayout& lastLayout() const override { return cached_ ? cached_->lastLayout() : decoded_->lastLayout(); }
  DecodeCounts lastCounts() const override { return cached_ ? cached_->lastCounts() : decoded_->lastCounts(); }

 private:
  std::unique_ptr<CachedScanSource> cached_;
  std::unique_ptr<TrialScanSource> decoded_;
  std::string path_;
  std::function<std::unique_ptr<TrialScanSource>()> decode_;
  std::string info_;
  std::size_t read_ = 0;
};

}  // namespace

std::unique_ptr<TrialScanSource> openCachedScans(const std::string& path,
                                                 const std::function<std::unique_ptr<TrialScanSource>()>& decode,
                                                 const std::string& info) {
  if (fs::exists(path)) {
    try {
      auto cached = std::make_unique<CachedScanSource>(path);
      cache::touch(path);  // used now: evicted last
      return std::make_unique<RecoveringScanSource>(std::move(cached), path, decode, info);
    } catch (const std::runtime_error& e) { removeDamaged(path, e.what()); }
  }
  return std::make_unique<CachingScanSource>(decode(), path, info);
}

}  // namespace cosmo::trials
