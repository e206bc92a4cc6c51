#pragma once
// Decoded scans of a trial kept on disk, so that a bag whose chunks are compressed (MCD: bz2, ≈ 50× the cost of
// the decode) is decompressed once, not on every run. The file holds every Scan exactly as decoded (stamp, float
// xyz / intensity / time, uint16 ring) and its DecodeCounts: reading it back gives bit-identical scans, so a
// run's output is the same with and without it. It is written through a temporary file renamed only when the
// trial was read to its end; a run stopped early leaves no cache. Used for ROS 1 bags with compressed chunks
// (ros_glue::openTrialScanSource). The key covers the bag (absolute path, size,
// modification time), the topic, the stamp convention and kScanCacheVersion.
#include <cstdint>
#include <fstream>
#include <functional>
#include <memory>
#include <string>

#include "cosmo/trials/trial_scans.hpp"

namespace cosmo::trials {

/// Bump when the decode changes what it produces.
inline constexpr std::uint32_t kScanCacheVersion = 1;

/// The cache folder: $COSMO_SCAN_CACHE, else $XDG_CACHE_HOME/cosmo/scans, else ~/.cache/cosmo/scans; empty
/// when $COSMO_SCAN_CACHE is "off".
std::string scanCacheDir();

/// `<dir>/<bag file name>-<16 hex digits>.scans` for this bag, topic and stamp convention.
std::string scanCachePath(const std::string& dir, const std::string& bag_path, const std::string& topic,
                          bool stamp_at_end);

/// The header stamps of a topic's first and last message as the bag's span reader found them
/// (ros_glue::readTrialSpan), kept beside the scans in `<dir>/<bag file name>-<16 hex digits>.span`: reading
/// them again costs the decompression of the first chunk and of every chunk of the bag's last seconds.
/// The key covers the bag (absolute path, size, modification time) and the topic.
std::string scanSpanPath(const std::string& dir, const std::string& bag_path, const std::string& topic);
/// False when `path` holds no complete span (missing, damaged).
bool readCachedSpan(const std::string& path, StampNs& first, StampNs& last);
/// Written through a temporary file; a failed write leaves no file.
void writeCachedSpan(const std::string& path, StampNs first, StampNs last);

/// Reads a complete cache file.
class CachedScanSource : public TrialScanSource {
 public:
  explicit CachedScanSource(const std::string& path);
  bool next(Scan& scan) override;
  std::size_t size() const override { return size_; }
  const CloudLayout& lastLayout() const override { return layout_; }
  DecodeCounts lastCounts() const override { return counts_; }

 private:
  std::uint64_t bytesLeft();  ///< of the file, after the read position

  std::string path_;
  std::ifstream in_;
  std::uint64_t file_size_ = 0;
  std::size_t size_ = 0, read_ = 0;
  CloudLayout layout_;  ///< stamp, height, width, point_step and fields of the last scan
  DecodeCounts counts_;
};

/// Passes a decoding source through and writes the cache as it goes; the file appears when `source` ends.
class CachingScanSource : public TrialScanSource {
 public:
  CachingScanSource(std::unique_ptr<TrialScanSource> source, const std::string& path);
  ~CachingScanSource() override;
  bool next(Scan& scan) override;
  std::size_t size() const override { return source_->size(); }
  const CloudLayout& lastLayout() const override { return source_->lastLayout(); }
  DecodeCounts lastCounts() const override { return source_->lastCounts(); }

 private:
  std::unique_ptr<TrialScanSource> source_;
  std::string path_, tmp_;
  std::ofstream out_;
  std::size_t written_ = 0;
  bool done_ = false;
};

/// The cached source when `path` holds a complete cache, else `decode()` wrapped in a CachingScanSource.
std::unique_ptr<TrialScanSource> openCachedScans(const std::string& path,
                                                 const std::function<std::unique_ptr<TrialScanSource>()>& decode);

}  // namespace cosmo::trials
