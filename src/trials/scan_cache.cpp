#include "cosmo/trials/scan_cache.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace cosmo::trials {

namespace {

constexpr char kMagic[10] = {'C', 'O', 'S', 'M', 'O', 'S', 'C', 'A', 'N', 'S'};
constexpr std::streamoff kCountOffset = sizeof(kMagic) + sizeof(std::uint32_t);

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

template <typename T>
void put(std::ofstream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof v);
}
template <typename T>
void putArray(std::ofstream& out, const std::vector<T>& v) {
  out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
}

/// Unique per process and per writer (two trials of one run may share a bag).
std::string temporaryName(const std::string& path) {
  static std::atomic<unsigned> writers{0};
  return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(writers++);
}

}  // namespace

std::string scanCacheDir() {
  if (const char* c = std::getenv("COSMO_SCAN_CACHE")) return std::string(c) == "off" ? "" : c;
  if (const char* x = std::getenv("XDG_CACHE_HOME")) return (fs::path(x) / "cosmo" / "scans").string();
  if (const char* h = std::getenv("HOME")) return (fs::path(h) / ".cache" / "cosmo" / "scans").string();
  return (fs::temp_directory_path() / "cosmo_scan_cache").string();
}

namespace {

/// The identity of a bag's topic: absolute path, size, modification time and the topic without its slash.
std::string bagKey(const std::string& bag_path, const std::string& topic) {
  const fs::path bag = fs::absolute(bag_path);
  const auto mtime = fs::last_write_time(bag).time_since_epoch().count();
  const std::string bare_topic = !topic.empty() && topic[0] == '/' ? topic.substr(1) : topic;
  return bag.string() + "\n" + std::to_string(fs::file_size(bag)) + "\n" + std::to_string(mtime) + "\n" + bare_topic;
}

std::string keyedPath(const std::string& dir, const std::string& bag_path, const std::string& key,
                      const char* extension) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a(key)));
  return (fs::path(dir) / (fs::path(bag_path).filename().string() + "-" + hex + extension)).string();
}

}  // namespace

std::string scanCachePath(const std::string& dir, const std::string& bag_path, const std::string& topic,
                          bool stamp_at_end) {
  const std::string key =
      bagKey(bag_path, topic) + "\n" + (stamp_at_end ? "end" : "start") + "\n" + std::to_string(kScanCacheVersion);
  return keyedPath(dir, bag_path, key, ".scans");
}

std::string scanSpanPath(const std::string& dir, const std::string& bag_path, const std::string& topic) {
  return keyedPath(dir, bag_path, bagKey(bag_path, topic) + "\nspan", ".span");
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

CachedScanSource::CachedScanSource(const std::string& path) : path_(path), in_(path, std::ios::binary) {
  std::error_code ec;
  file_size_ = fs::file_size(path, ec);
  if (ec) file_size_ = 0;
  char magic[sizeof kMagic] = {};
  std::uint32_t version = 0;
  std::uint64_t count = 0;
  in_.read(magic, sizeof magic);
  in_.read(reinterpret_cast<char*>(&version), sizeof version);
  in_.read(reinterpret_cast<char*>(&count), sizeof count);
  if (!in_ || std::memcmp(magic, kMagic, sizeof kMagic) != 0 || version != kScanCacheVersion)
    throw std::runtime_error(path + ": not a scan cache of version " + std::to_string(kScanCacheVersion) +
                             " (delete it to rebuild it)");
  size_ = static_cast<std::size_t>(count);
}

bool CachedScanSource::next(Scan& scan) {
  if (read_ >= size_) return false;
  std::uint64_t stamp = 0, points = 0, invalid = 0;
  std::uint32_t n = 0, height = 0, width = 0;
  std::uint8_t flags = 0;
  auto get = [&](auto& v) { in_.read(reinterpret_cast<char*>(&v), sizeof v); };
  std::uint32_t point_step = 0, nfields = 0;
  get(stamp), get(n), get(flags), get(points), get(invalid), get(height), get(width), get(point_step), get(nfields);
  if (!in_ || nfields > 1024)
    throw std::runtime_error(path_ + ": scan cache damaged at scan " + std::to_string(read_) +
                             " (delete it to rebuild it)");
  // Every point holds at least its 12 bytes of xyz: a count the rest of the file cannot hold is damage, not an
  // allocation to attempt.
  if (static_cast<std::uint64_t>(n) * 12 > bytesLeft())
    throw std::runtime_error(path_ + ": scan cache damaged at scan " + std::to_string(read_) + " (" +
                             std::to_string(n) + " points; delete it to rebuild it)");
  layout_.fields.resize(nfields);
  for (auto& f : layout_.fields) {
    std::uint32_t len = 0;
    get(len);
    if (!in_ || len > 4096) throw std::runtime_error(path_ + ": scan cache damaged (delete it to rebuild it)");
    f.name.resize(len);
    in_.read(f.name.data(), len);
    get(f.offset), get(f.datatype), get(f.count);
  }
  auto getArray = [&](auto& v, bool present) {
    v.resize(present ? n : 0);
    in_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(v[0])));
  };
  getArray(scan.points, true);
  getArray(scan.intensity, flags & 1);
  getArray(scan.time, flags & 2);
  getArray(scan.ring, flags & 4);
  if (!in_)
    throw std::runtime_error(path_ + ": scan cache truncated at scan " + std::to_string(read_) +
                             " (delete it to rebuild it)");
  scan.stamp = stamp;
  counts_ = {static_cast<std::size_t>(points), static_cast<std::size_t>(invalid)};
  layout_.stamp = stamp;
  layout_.height = height;
  layout_.width = width;
  layout_.point_step = point_step;
  ++read_;
  return true;
}

CachingScanSource::CachingScanSource(std::unique_ptr<TrialScanSource> source, const std::string& path)
    : source_(std::move(source)), path_(path), tmp_(temporaryName(path)) {
  fs::create_directories(fs::path(path).parent_path());
  out_.open(tmp_, std::ios::binary | std::ios::trunc);
  if (!out_) throw std::runtime_error(tmp_ + ": cannot write the scan cache");
  out_.write(kMagic, sizeof kMagic);
  put(out_, kScanCacheVersion);
  put(out_, std::uint64_t{0});  // the count, written when complete
}

CachingScanSource::~CachingScanSource() {
  if (done_) return;
  out_.close();
  std::error_code ec;
  fs::remove(tmp_, ec);  // not read to its end: no cache
}

bool CachingScanSource::next(Scan& scan) {
  if (!source_->next(scan)) {
    if (!done_) {
      out_.seekp(kCountOffset);
      put(out_, static_cast<std::uint64_t>(written_));
      const bool ok = static_cast<bool>(out_);
      out_.close();
      std::error_code ec;
      if (ok && !out_.fail()) fs::rename(tmp_, path_, ec);
      if (!ok || out_.fail() || ec) fs::remove(tmp_, ec);  // a failed write (disk full) leaves no cache
      done_ = true;
    }
    return false;
  }
  const DecodeCounts c = source_->lastCounts();
  const CloudLayout& L = source_->lastLayout();
  const auto flags =
      static_cast<std::uint8_t>((scan.hasIntensity() ? 1 : 0) | (scan.hasTime() ? 2 : 0) | (scan.hasRing() ? 4 : 0));
  put(out_, static_cast<std::uint64_t>(scan.stamp));
  put(out_, static_cast<std::uint32_t>(scan.size()));
  put(out_, flags);
  put(out_, static_cast<std::uint64_t>(c.points));
  put(out_, static_cast<std::uint64_t>(c.invalid));
  put(out_, L.height);
  put(out_, L.width);
  put(out_, L.point_step);
  put(out_, static_cast<std::uint32_t>(L.fields.size()));
  for (const auto& f : L.fields) {
    put(out_, static_cast<std::uint32_t>(f.name.size()));
    out_.write(f.name.data(), static_cast<std::streamsize>(f.name.size()));
    put(out_, f.offset);
    put(out_, f.datatype);
    put(out_, f.count);
  }
  putArray(out_, scan.points);
  if (flags & 1) putArray(out_, scan.intensity);
  if (flags & 2) putArray(out_, scan.time);
  if (flags & 4) putArray(out_, scan.ring);
  ++written_;
  return true;
}

std::unique_ptr<TrialScanSource> openCachedScans(const std::string& path,
                                                 const std::function<std::unique_ptr<TrialScanSource>()>& decode) {
  if (fs::exists(path)) return std::make_unique<CachedScanSource>(path);
  return std::make_unique<CachingScanSource>(decode(), path);
}

}  // namespace cosmo::trials
