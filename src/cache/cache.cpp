#include "cosmo/cache/cache.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <stdexcept>

namespace fs = std::filesystem;

namespace cosmo::cache {

const char* kindName(Kind kind) { return kind == Kind::Scan ? "scan" : "sim"; }

Kind parseKind(const std::string& name) {
  if (name == "scan" || name == "scans") return Kind::Scan;
  if (name == "sim") return Kind::Sim;
  throw std::invalid_argument("unknown cache '" + name + "' (scan or sim)");
}

fs::path cacheRoot(Kind kind) {
  const bool scan = kind == Kind::Scan;
  if (const char* c = std::getenv(scan ? "COSMO_SCAN_CACHE" : "COSMO_SIM_CACHE"))
    return scan && std::string(c) == "off" ? fs::path() : fs::path(c);
  const char* folder = scan ? "scans" : "sim";
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "cosmo" / folder;
  if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".cache" / "cosmo" / folder;
  return fs::temp_directory_path() / (scan ? "cosmo_scan_cache" : "cosmo_sim_cache");
}

const char* maxSizeVariable(Kind kind) {
  return kind == Kind::Scan ? "COSMO_SCAN_CACHE_MAX_SIZE" : "COSMO_SIM_CACHE_MAX_SIZE";
}

std::uint64_t defaultMaxSize(Kind kind) { return (kind == Kind::Scan ? 100ULL : 20ULL) << 30; }

std::uint64_t maxSize(Kind kind) {
  const char* v = std::getenv(maxSizeVariable(kind));
  return v ? parseSize(v, maxSizeVariable(kind)) : defaultMaxSize(kind);
}

std::uint64_t parseSize(const std::string& text, const std::string& what) {
  auto bad = [&]() {
    return std::invalid_argument(
        what + ": expected a size (bytes, or a number with a K, M, G or T suffix, e.g. 100G), got '" + text + "'");
  };
  std::size_t i = 0;
  while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.')) ++i;
  if (i == 0 || std::count(text.begin(), text.begin() + i, '.') > 1) throw bad();
  const double number = std::strtod(text.substr(0, i).c_str(), nullptr);
  std::string suffix = text.substr(i);
  if (suffix.size() == 2 && (suffix[1] == 'B' || suffix[1] == 'b') && suffix[0] != 'B' && suffix[0] != 'b')
    suffix.pop_back();  // "100GB" as "100G"
  double unit = 1;
  if (suffix.empty() || suffix == "B" || suffix == "b")
    unit = 1;
  else if (suffix == "K" || suffix == "k")
    unit = 1024.0;
  else if (suffix == "M" || suffix == "m")
    unit = 1024.0 * 1024;
  else if (suffix == "G" || suffix == "g")
    unit = 1024.0 * 1024 * 1024;
  else if (suffix == "T" || suffix == "t")
    unit = 1024.0 * 1024 * 1024 * 1024;
  else
    throw bad();
  const double bytes = number * unit;
  if (!std::isfinite(bytes) || bytes >= 1.8e19) throw bad();
  return static_cast<std::uint64_t>(std::llround(bytes));
}

std::string formatSize(std::uint64_t bytes) {
  const char* units[] = {"B", "K", "M", "G", "T"};
  double v = static_cast<double>(bytes);
  int u = 0;
  while (v >= 1024 && u < 4) v /= 1024, ++u;
  char out[32];
  const bool whole = u == 0 || v >= 100 || v == static_cast<double>(static_cast<std::uint64_t>(v));
  std::snprintf(out, sizeof out, whole ? "%.0f%s" : "%.1f%s", v, units[u]);
  return out;
}

std::string formatAge(fs::file_time_type t) {
  const double s = std::chrono::duration<double>(fs::file_time_type::clock::now() - t).count();
  char out[32];
  if (s < 120)
    std::snprintf(out, sizeof out, "%.0f s", std::max(0.0, s));
  else if (s < 7200)
    std::snprintf(out, sizeof out, "%.0f min", s / 60);
  else if (s < 2 * 86400)
    std::snprintf(out, sizeof out, "%.0f h", s / 3600);
  else
    std::snprintf(out, sizeof out, "%.0f days", s / 86400);
  return out;
}

namespace {

/// The writing process of a temporary ("<name>.tmp-<pid>[-<n>]") or of an item being removed
/// (".removing-<pid>-<name>"); 0 when the name holds none.
long ownerPid(const std::string& name) {
  std::size_t at = name.find(".tmp-");
  if (at != std::string::npos)
    at += 5;
  else if (name.rfind(".removing-", 0) == 0)
    at = 10;
  else
    return 0;
  return std::strtol(name.c_str() + at, nullptr, 10);
}

bool pending(const std::string& name) { return name.find(".tmp-") != std::string::npos || name[0] == '.'; }

bool processGone(long pid) { return pid <= 0 || (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH); }

std::uint64_t bytesOf(const fs::path& p) {
  std::error_code ec;
  const fs::file_status s = fs::symlink_status(p, ec);
  if (ec) return 0;
  if (fs::is_regular_file(s)) {
    const auto n = fs::file_size(p, ec);
    return ec ? 0 : n;
  }
  if (!fs::is_directory(s)) return 0;
  std::uint64_t total = 0;
  for (auto it = fs::recursive_directory_iterator(p, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (it->is_regular_file(ec) && !it->is_symlink(ec)) total += it->file_size(ec);
  return total;
}

std::string firstLine(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  return line;
}

/// An exclusive flock on every path (none in use), released when it goes.
struct ExclusiveHold {
  std::vector<int> fds;
  bool held = true;
  explicit ExclusiveHold(const std::vector<fs::path>& paths) {
    for (const auto& p : paths) {
      const int fd = ::open(p.c_str(), O_RDONLY | O_CLOEXEC);
      if (fd < 0) continue;  // gone meanwhile: nothing to hold
      fds.push_back(fd);
      if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        held = false;
        return;
      }
    }
  }
  ~ExclusiveHold() {
    for (int fd : fds) ::close(fd);
  }
};

std::atomic<unsigned> removals{0};

}  // namespace

std::vector<Entry> listEntries(const fs::path& root) {
  std::map<std::string, Entry> by_id;
  std::error_code ec;
  if (root.empty() || !fs::is_directory(root, ec)) return {};
  for (const auto& item : fs::directory_iterator(root, ec)) {
    const std::string name = item.path().filename().string();
    if (name.empty() || pending(name)) continue;
    const bool folder = item.is_directory(ec) && !item.is_symlink(ec);
    const std::string id = folder ? name : item.path().stem().string();
    Entry& e = by_id[id];
    e.id = id;
    e.folder = e.folder || folder;
    e.paths.push_back(item.path());
    e.bytes += bytesOf(item.path());
    const auto t = fs::last_write_time(item.path(), ec);
    if (!ec && (e.paths.size() == 1 || t > e.last_used)) e.last_used = t;
    if (folder)
      e.info = firstLine(item.path() / kFolderInfoName);
    else if (item.path().extension() == ".info")
      e.info = firstLine(item.path());
  }
  std::vector<Entry> out;
  for (auto& [id, e] : by_id) {
    std::sort(e.paths.begin(), e.paths.end());
    out.push_back(std::move(e));
  }
  std::stable_sort(out.begin(), out.end(), [](const Entry& a, const Entry& b) { return a.last_used < b.last_used; });
  return out;
}

std::uint64_t pendingBytes(const fs::path& root) {
  std::uint64_t total = 0;
  std::error_code ec;
  if (root.empty() || !fs::is_directory(root, ec)) return 0;
  for (const auto& item : fs::directory_iterator(root, ec))
    if (pending(item.path().filename().string())) total += bytesOf(item.path());
  return total;
}

void touch(const fs::path& path) {
  std::error_code ec;
  fs::last_write_time(path, fs::file_time_type::clock::now(), ec);  // a read-only cache only ages
}

fs::path infoPathOf(const fs::path& entry_file) {
  fs::path p = entry_file;
  return p.replace_extension(".info");
}

void writeInfo(const fs::path& info_path, const std::string& line) {
  std::error_code ec;
  fs::create_directories(info_path.parent_path(), ec);
  const fs::path tmp = info_path.string() + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(removals++);
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << line << "\n";
    if (!out) {
      fs::remove(tmp, ec);
      return;
    }
  }
  fs::rename(tmp, info_path, ec);
  if (ec) fs::remove(tmp, ec);
}

bool removeEntry(const fs::path& root, const Entry& entry) {
  ExclusiveHold hold(entry.paths);
  if (!hold.held) return false;
  // Out of its name first, the data before its description: a reader finds the whole entry or none of its data.
  std::vector<fs::path> order = entry.paths;
  std::stable_partition(order.begin(), order.end(), [](const fs::path& p) { return p.extension() != ".info"; });
  bool any = false;
  for (const auto& p : order) {
    const fs::path away = root / (".removing-" + std::to_string(::getpid()) + "-" + std::to_string(removals++) + "-" +
                                  p.filename().string());
    std::error_code ec;
    fs::rename(p, away, ec);
    if (ec) continue;  // removed by another process meanwhile
    any = true;
    fs::remove_all(away, ec);
  }
  return any;
}

Eviction enforceLimit(const fs::path& root, std::uint64_t max_bytes, const std::string& keep) {
  Eviction ev;
  std::vector<Entry> entries = listEntries(root);
  std::uint64_t total = pendingBytes(root);
  for (const auto& e : entries) total += e.bytes;
  ev.bytes_before = ev.bytes_after = total;
  for (const auto& e : entries) {
    if (ev.bytes_after <= max_bytes) break;
    if (e.id == keep) continue;
    if (removeEntry(root, e)) {
      ev.bytes_after -= std::min(ev.bytes_after, e.bytes);
      ev.removed.push_back(e);
    }
  }
  return ev;
}

Cleared clear(const fs::path& root, const std::string& id) {
  Cleared c;
  const std::vector<Entry> entries = listEntries(root);
  bool found = id.empty();
  for (const auto& e : entries) {
    if (!id.empty() && e.id != id) continue;
    found = true;
    if (removeEntry(root, e)) {
      c.removed.push_back(e);
      c.bytes += e.bytes;
    } else {
      c.kept.push_back(e);
    }
  }
  if (!found) throw std::invalid_argument("no entry '" + id + "' in " + root.string());
  std::error_code ec;
  if (id.empty() && fs::is_directory(root, ec))
    for (const auto& item : fs::directory_iterator(root, ec)) {
      const std::string name = item.path().filename().string();
      if (pending(name) && processGone(ownerPid(name))) {
        c.bytes += bytesOf(item.path());
        fs::remove_all(item.path(), ec);
      }
    }
  return c;
}

EntryUse::EntryUse(const fs::path& path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ >= 0 && ::flock(fd_, LOCK_SH | LOCK_NB) != 0) {
    // An evictor holds it for the moment it takes to rename it away: the open file stays readable.
    ::close(fd_);
    fd_ = -1;
  }
}

EntryUse::~EntryUse() {
  if (fd_ >= 0) ::close(fd_);
}

Eviction applyLimit(Kind kind, const fs::path& root, const std::string& keep) {
  const std::uint64_t limit = maxSize(kind);
  Eviction ev = enforceLimit(root, limit, keep);
  for (const auto& e : ev.removed)
    std::cerr << "cosmo cache (" << kindName(kind) << "): removed " << e.id << " (" << formatSize(e.bytes)
              << ", last used " << formatAge(e.last_used) << " ago) to stay under " << maxSizeVariable(kind) << "="
              << formatSize(limit) << "\n";
  if (ev.bytes_after > limit)
    std::cerr << "cosmo cache (" << kindName(kind) << "): " << root.string() << " holds " << formatSize(ev.bytes_after)
              << ", above " << maxSizeVariable(kind) << "=" << formatSize(limit)
              << " (the entry just written and entries in use are kept)\n";
  return ev;
}

}  // namespace cosmo::cache

namespace cosmo::cache {

namespace {

constexpr std::uint64_t kP1 = 11400714785074694791ULL, kP2 = 14029467366897019727ULL, kP3 = 1609587929392839161ULL,
                        kP4 = 9650029242287828579ULL, kP5 = 2870177450012600261ULL;

inline std::uint64_t rotl(std::uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }
inline std::uint64_t round64(std::uint64_t acc, std::uint64_t w) { return rotl(acc + w * kP2, 31) * kP1; }
inline std::uint64_t load64(const unsigned char* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}

}  // namespace

std::uint64_t hashBytes(const void* data, std::size_t size, std::uint64_t seed) {
  const auto* p = static_cast<const unsigned char*>(data);
  const unsigned char* end = p + size;
  std::uint64_t h;
  if (size >= 32) {
    std::uint64_t v[4] = {seed + kP1 + kP2, seed + kP2, seed, seed - kP1};
    for (; end - p >= 32; p += 32)
      for (int l = 0; l < 4; ++l) v[l] = round64(v[l], load64(p + 8 * l));
    h = rotl(v[0], 1) + rotl(v[1], 7) + rotl(v[2], 12) + rotl(v[3], 18);
    for (int l = 0; l < 4; ++l) h = (h ^ round64(0, v[l])) * kP1 + kP4;
  } else {
    h = seed + kP5;
  }
  h += static_cast<std::uint64_t>(size);
  for (; end - p >= 8; p += 8) h = rotl(h ^ round64(0, load64(p)), 27) * kP1 + kP4;
  for (; p < end; ++p) h = rotl(h ^ (*p * kP5), 11) * kP1;
  h ^= h >> 33;
  h *= kP2;
  h ^= h >> 29;
  h *= kP3;
  h ^= h >> 32;
  return h;
}

std::uint64_t fileIdentity(const fs::path& file) {
  constexpr std::uint64_t kEdge = 1 << 20, kBlock = 64 << 10, kSamples = 16;
  std::ifstream in(file, std::ios::binary);
  std::error_code ec;
  const std::uint64_t size = fs::file_size(file, ec);
  if (!in || ec) throw std::runtime_error(file.string() + ": cannot read it to identify it");
  std::string buffer;
  std::uint64_t h = hashBytes(&size, sizeof size);
  auto hashRange = [&](std::uint64_t at, std::uint64_t n) {
    buffer.resize(n);
    in.seekg(static_cast<std::streamoff>(at));
    in.read(buffer.data(), static_cast<std::streamsize>(n));
    if (!in) throw std::runtime_error(file.string() + ": cannot read it to identify it");
    h = hashBytes(buffer.data(), n, h);
  };
  if (size < 3 * kEdge) {
    hashRange(0, size);
    return h;
  }
  hashRange(0, kEdge);
  const std::uint64_t span = size - 2 * kEdge - kBlock;  // where the samples start, between the edges
  for (std::uint64_t k = 0; k < kSamples; ++k) hashRange(kEdge + span * k / (kSamples - 1), kBlock);
  hashRange(size - kEdge, kEdge);
  return h;
}

}  // namespace cosmo::cache
