// The scan cache (trials/scan_cache.hpp): scans read back bit-identical, plain and compressed; a damaged entry is
// removed with a warning and the scans decoded again, never a crash; the key follows the bag's content, not its
// path. The scans come from a source in memory (a few hundred points each) and the cache goes to a folder of the
// test's own, removed at its end (never the user's ~/.cache).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>

#include "cosmo/common/whole_file.hpp"
#include "cosmo/trials/scan_cache.hpp"

namespace fs = std::filesystem;
using namespace cosmo;

namespace {

struct TempRoot {
  fs::path path = fs::temp_directory_path() / ("cosmo_scan_cache_test_" + std::to_string(::getpid()) + "_" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempRoot() {
    fs::remove_all(path);
    fs::create_directories(path);
    ::setenv("COSMO_SCAN_CACHE", (path / "scans").c_str(), 1);
    ::unsetenv("COSMO_SCAN_CACHE_MAX_SIZE");
  }
  ~TempRoot() { fs::remove_all(path); }
};

/// Scans with every field (one without intensity, time and ring), odd floats included: -0, NaN payloads,
/// denormals, infinities.
std::vector<Scan> makeScans(int count = 6) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-50.f, 50.f);
  std::vector<Scan> scans(count);
  for (int k = 0; k < count; ++k) {
    Scan& s = scans[k];
    s.stamp = 1'000'000'000LL * (k + 1) + 123;
    const std::size_t n = 200 + 37 * k;
    for (std::size_t i = 0; i < n; ++i) {
      s.points.emplace_back(u(rng), u(rng), u(rng) * 0.1f);
      if (k != 2) {
        s.intensity.push_back(std::floor(u(rng) + 50));
        s.time.push_back(-0.1f + 0.1f * static_cast<float>(i) / n);
        s.ring.push_back(static_cast<std::uint16_t>(i % 16));
      }
    }
    s.points[0].x() = -0.0f;
    s.points[1].y() = std::numeric_limits<float>::denorm_min();
    s.points[2].z() = std::numeric_limits<float>::infinity();
    std::uint32_t nan_bits = 0x7fc01234;
    std::memcpy(&s.points[3].x(), &nan_bits, 4);
  }
  return scans;
}

/// The scans, as a decoder would give them.
class MemorySource : public trials::TrialScanSource {
 public:
  explicit MemorySource(std::vector<Scan> scans, int* opened = nullptr) : scans_(std::move(scans)) {
    if (opened) ++*opened;
    layout_.height = 16;
    layout_.fields = {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"ring", 12, 4, 1}};
    layout_.point_step = 14;
  }
  bool next(Scan& scan) override {
    if (k_ >= scans_.size()) return false;
    scan = scans_[k_++];
    layout_.stamp = scan.stamp;
    layout_.width = static_cast<std::uint32_t>(scan.size() / 16);
    return true;
  }
  std::size_t size() const override { return scans_.size(); }
  const trials::CloudLayout& lastLayout() const override { return layout_; }
  trials::DecodeCounts lastCounts() const override { return {scans_[k_ - 1].size() + 5, 5}; }

 private:
  std::vector<Scan> scans_;
  std::size_t k_ = 0;
  trials::CloudLayout layout_;
};

void expectBitIdentical(const Scan& a, const Scan& b, std::size_t k) {
  ASSERT_EQ(a.stamp, b.stamp) << k;
  ASSERT_EQ(a.size(), b.size()) << k;
  ASSERT_EQ(a.intensity.size(), b.intensity.size()) << k;
  ASSERT_EQ(a.time.size(), b.time.size()) << k;
  EXPECT_EQ(std::memcmp(a.points.data(), b.points.data(), a.size() * sizeof(a.points[0])), 0) << k;
  EXPECT_EQ(std::memcmp(a.intensity.data(), b.intensity.data(), a.intensity.size() * 4), 0) << k;
  EXPECT_EQ(std::memcmp(a.time.data(), b.time.data(), a.time.size() * 4), 0) << k;
  EXPECT_EQ(a.ring, b.ring) << k;
}

/// Fills the cache at `path` through a CachingScanSource and returns what it passed on.
std::vector<Scan> fill(const std::string& path, const std::vector<Scan>& scans, trials::ScanCompression c) {
  trials::CachingScanSource caching(std::make_unique<MemorySource>(scans), path, "trial test", c);
  std::vector<Scan> out;
  for (Scan s; caching.next(s);) out.push_back(s);
  return out;
}

std::vector<Scan> readAll(trials::TrialScanSource& source) {
  std::vector<Scan> out;
  for (Scan s; source.next(s);) out.push_back(s);
  return out;
}

}  // namespace

TEST(ScanCache, PlainAndCompressedReadBackBitIdentical) {
  TempRoot t;
  const std::vector<Scan> scans = makeScans();
  std::uint64_t sizes[2] = {};
  for (auto c : {trials::ScanCompression::None, trials::ScanCompression::Lz4}) {
    const std::string path = (t.path / "scans" / (c == trials::ScanCompression::None ? "p.scans" : "c.scans")).string();
    const std::vector<Scan> passed = fill(path, scans, c);
    ASSERT_EQ(passed.size(), scans.size());
    ASSERT_TRUE(fs::exists(path));
    EXPECT_EQ(readWholeFileOrEmpty(cache::infoPathOf(path).string()), "trial test\n");
    sizes[static_cast<int>(c)] = fs::file_size(path);
    trials::CachedScanSource cached(path);
    EXPECT_EQ(cached.size(), scans.size());
    std::size_t k = 0;
    for (Scan s; cached.next(s); ++k) {
      expectBitIdentical(scans[k], s, k);
      EXPECT_EQ(cached.lastCounts().points, scans[k].size() + 5);
      EXPECT_EQ(cached.lastLayout().fields.size(), 4u);
      EXPECT_EQ(cached.lastLayout().fields[3].name, "ring");
      EXPECT_EQ(cached.lastLayout().point_step, 14u);
    }
    EXPECT_EQ(k, scans.size());
  }
  EXPECT_LT(sizes[1], sizes[0]);  // ring and time planes compress even in random points
}

TEST(ScanCache, CompressionFromTheEnvironment) {
  TempRoot t;
  ::unsetenv("COSMO_SCAN_CACHE_COMPRESSION");
  EXPECT_EQ(trials::scanCacheCompression(), trials::ScanCompression::Lz4);
  ::setenv("COSMO_SCAN_CACHE_COMPRESSION", "none", 1);
  EXPECT_EQ(trials::scanCacheCompression(), trials::ScanCompression::None);
  ::setenv("COSMO_SCAN_CACHE_COMPRESSION", "zstd", 1);
  EXPECT_THROW(trials::scanCacheCompression(), std::invalid_argument);
  ::unsetenv("COSMO_SCAN_CACHE_COMPRESSION");
}

TEST(ScanCache, ADamagedEntryIsRebuiltWithAWarning) {
  TempRoot t;
  const std::vector<Scan> scans = makeScans();
  const std::string path = (t.path / "scans" / "d.scans").string();
  fill(path, scans, trials::ScanCompression::Lz4);
  const std::string good = readWholeFileOrEmpty(path);
  // A flipped byte in the fourth scan's record, a truncation after the second, a header that is no cache's.
  std::vector<std::string> damaged = {good, good.substr(0, good.size() * 2 / 5), "not a cache at all"};
  damaged[0][good.size() * 3 / 5] ^= 0x20;
  for (std::size_t d = 0; d < damaged.size(); ++d) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << damaged[d];
    int decodes = 0;
    testing::internal::CaptureStderr();
    auto source = trials::openCachedScans(path, [&]() { return std::make_unique<MemorySource>(scans, &decodes); });
    const std::vector<Scan> got = readAll(*source);
    const std::string err = testing::internal::GetCapturedStderr();
    source.reset();
    EXPECT_EQ(decodes, 1) << d;
    ASSERT_EQ(got.size(), scans.size()) << d;
    for (std::size_t k = 0; k < got.size(); ++k) expectBitIdentical(scans[k], got[k], k);
    EXPECT_NE(err.find("warning: " + path), std::string::npos) << d << ": " << err;
    EXPECT_NE(err.find("decoded again"), std::string::npos) << err;
    // Rebuilt: the same bytes as the good one.
    EXPECT_EQ(readWholeFileOrEmpty(path), good) << d;
  }
  // A complete entry is read without a decode.
  int decodes = 0;
  auto source = trials::openCachedScans(path, [&]() { return std::make_unique<MemorySource>(scans, &decodes); });
  EXPECT_EQ(readAll(*source).size(), scans.size());
  EXPECT_EQ(decodes, 0);
}

TEST(ScanCache, KeyFollowsTheBagsContentNotItsPath) {
  TempRoot t;
  const fs::path data = t.path / "data";
  fs::create_directories(data);
  std::ofstream(data / "a.bag", std::ios::binary) << std::string(5000, 'a') << "tail";
  fs::create_directory_symlink(data, t.path / "linked_root");
  const std::string dir = (t.path / "scans").string();
  const std::string key = trials::scanCachePath(dir, (data / "a.bag").string(), "/points", true);
  EXPECT_EQ(fs::path(key).extension(), ".scans");
  EXPECT_EQ(trials::scanCachePath(dir, (t.path / "linked_root" / "a.bag").string(), "/points", true), key);
  EXPECT_EQ(trials::scanCachePath(dir, (data / "a.bag").string(), "points", true), key);  // the same topic
  EXPECT_NE(trials::scanCachePath(dir, (data / "a.bag").string(), "/points", false), key);
  EXPECT_NE(trials::scanCachePath(dir, (data / "a.bag").string(), "/other", true), key);
  EXPECT_EQ(fs::path(trials::scanSpanPath(dir, (data / "a.bag").string(), "/points", true)).stem(),
            fs::path(key).stem());  // one entry
  // Another bag of the same size (and later modification time): another key.
  std::ofstream(data / "b.bag", std::ios::binary) << std::string(5000, 'a') << "tall";
  EXPECT_NE(trials::scanCachePath(dir, (data / "b.bag").string(), "/points", true), key);
}
