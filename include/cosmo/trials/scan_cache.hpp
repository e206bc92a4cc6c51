#pragma once
// Decoded scans of a trial kept on disk, so that a bag whose chunks are compressed (MCD: bz2, ≈ 50× the cost of
// the decode) is decompressed once, not on every run. The file holds every Scan exactly as decoded (stamp, float
// xyz / intensity / time, uint16 ring) and its DecodeCounts: reading it back gives bit-identical scans, so a
// run's output is the same with and without it. Each scan's record is checked on reading (a hash of its bytes);
// it is stored plain or compressed (byte planes, then LZ4: COSMO_SCAN_CACHE_COMPRESSION, scanCacheCompression).
// It is written through a temporary file renamed only when the trial was read to its end; a run stopped early
// leaves no cache. Used for ROS 1 bags with compressed chunks (trials::openTrialScanSource). The cache is one of
// cosmo::cache's (cache/cache.hpp): its size limit, listing and clearing are there.
//
// The key covers the bag's content identity (cache::fileIdentity: size and sampled blocks, not its path, so a
// bag reached through a symlinked data root is the same entry), the topic, the stamp convention and
// kScanCacheVersion.
#include <cstdint>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cosmo/cache/cache.hpp"
#include "cosmo/trials/trial_scans.hpp"

namespace cosmo::trials {

/// Bump when the decode changes what it produces or the file format changes.
inline constexpr std::uint32_t kScanCacheVersion = 2;

/// How scans are stored: None (the arrays as they are in memory) or Lz4 (each array's bytes split into byte
/// planes, then LZ4; docs/benchmarks.md measures both).
enum class ScanCompression : std::uint8_t { None = 0, Lz4 = 1 };
/// $COSMO_SCAN_CACHE_COMPRESSION: "lz4" (default) or "none"; throws std::invalid_argument on another value.
ScanCompression scanCacheCompression();

/// The cache folder: cache::cacheRoot(cache::Kind::Scan) ($COSMO_SCAN_CACHE, else $XDG_CACHE_HOME/cosmo/scans,
/// else ~/.cache/cosmo/scans); empty when $COSMO_SCAN_CACHE is "off".
std::string scanCacheDir();

/// `<dir>/<16 hex digits>.scans` for this bag's content, topic and stamp convention.
std::string scanCachePath(const std::string& dir, const std::string& bag_path, const std::string& topic,
                          bool stamp_at_end);

/// The header stamps of a topic's first and last message as the bag's span reader found them
/// (trials::readTrialSpan), kept beside the scans (same entry, `.span`): reading them again costs the
/// decompression of the first chunk and of every chunk of the bag's last seconds.
std::string scanSpanPath(const std::string& dir, const std::string& bag_path, const std::string& topic,
                         bool stamp_at_end);
/// False when `path` holds no complete span (missing, damaged).
bool readCachedSpan(const std::string& path, StampNs& first, StampNs& last);
/// Written through a temporary file; a failed write leaves no file.
void writeCachedSpan(const std::string& path, StampNs first, StampNs last);

/// Reads a complete cache file (either compression). Throws std::runtime_error naming the file and the scan on
/// a file that is not one, damaged or truncated.
class CachedScanSource : public TrialScanSource {
 public:
  explicit CachedScanSource(const std::string& path);
  ~CachedScanSource() override;
  bool next(Scan& scan) override;
  std::size_t size() const override { return size_; }
  const CloudLayout& lastLayout() const override { return layout_; }
  DecodeCounts lastCounts() const override { return counts_; }

 private:
  std::uint64_t bytesLeft();  ///< of the file, after the read position
  [[noreturn]] void damaged(const std::string& why) const;

  std::string path_;
  std::ifstream in_;
  std::unique_ptr<cache::EntryUse> hold_;  ///< the cache entry is in use while this reads it
  std::uint64_t file_size_ = 0;
  std::size_t size_ = 0, read_ = 0;
  ScanCompression compression_ = ScanCompression::None;
  std::vector<char> record_, raw_;  ///< the last record as stored, and its arrays decompressed
  CloudLayout layout_;              ///< stamp, height, width, point_step and fields of the last scan
  DecodeCounts counts_;
};

/// Passes a decoding source through and writes the cache as it goes; the file appears when `source` ends.
class CachingScanSource : public TrialScanSource {
 public:
  /// `info`: one line saying what the entry holds (cache::writeInfo); `compression`: how scans are stored.
  CachingScanSource(std::unique_ptr<TrialScanSource> source, const std::string& path, const std::string& info = "",
                    ScanCompression compression = scanCacheCompression());
  ~CachingScanSource() override;
  bool next(Scan& scan) override;
  std::size_t size() const override { return source_->size(); }
  const CloudLayout& lastLayout() const override { return source_->lastLayout(); }
  DecodeCounts lastCounts() const override { return source_->lastCounts(); }

 private:
  void finish();

  std::unique_ptr<TrialScanSource> source_;
  std::string path_, tmp_, info_;
  std::ofstream out_;
  ScanCompression compression_;
  std::vector<char> record_, raw_;
  std::size_t written_ = 0;
  bool done_ = false;
};

/// The cached source when `path` holds a complete cache, else `decode()` wrapped in a CachingScanSource (`info`
/// describes the entry). A cache found damaged (on opening it or at any scan) is removed with a warning on stderr
/// and the bag decoded instead, from the same scan on: the scans given are the decode's either way; the cache is
/// written again by that read if it goes to the end.
std::unique_ptr<TrialScanSource> openCachedScans(const std::string& path,
                                                 const std::function<std::unique_ptr<TrialScanSource>()>& decode,
                                                 const std::string& info = "");

}  // namespace cosmo::trials
