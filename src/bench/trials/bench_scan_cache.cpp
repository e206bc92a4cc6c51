// bench_scan_cache: what the scan cache (trials/scan_cache.hpp) costs per scan, plain and compressed (byte
// planes + LZ4): bytes on disk, write time, and the warm read (the file in the page cache, as a run finds the
// entry it wrote: the median of --repeat passes over every scan), on real scans (KITTI .bin files: xyz +
// reflectance, cycled to --scans scans so that a pass reads as many as a trial's source does) and on the scans of ROS 1
// bags (e.g. an MCD-layout bag of cosmo_simulate: xyz, intensity, time, ring). Checks that both read back
// bit-identical. The cache files go to --dir (removed at the end).
//
//   bench_scan_cache [--kitti DIR] [--scans N] [--repeat N] [--dir DIR] [BAG[:TOPIC] ...]
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "cosmo/bench/stopwatch.hpp"
#include "cosmo/common/command_line.hpp"
#include "cosmo/trials/scan_cache.hpp"
#include "cosmo/trials/trial_scans.hpp"

using namespace cosmo;
namespace fs = std::filesystem;

namespace {

class MemorySource : public trials::TrialScanSource {
 public:
  explicit MemorySource(const std::vector<Scan>& scans) : scans_(scans) {}
  bool next(Scan& scan) override {
    if (k_ >= scans_.size()) return false;
    scan = scans_[k_++];
    return true;
  }
  std::size_t size() const override { return scans_.size(); }
  const trials::CloudLayout& lastLayout() const override { return layout_; }
  trials::DecodeCounts lastCounts() const override { return {scans_[k_ - 1].size(), 0}; }

 private:
  const std::vector<Scan>& scans_;
  std::size_t k_ = 0;
  trials::CloudLayout layout_;
};

std::vector<Scan> readKitti(const fs::path& dir, std::size_t limit) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".bin") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::vector<Scan> scans;
  for (std::size_t k = 0; scans.size() < limit && !files.empty(); ++k) {
    const fs::path& f = files[k % files.size()];  // cycled: a pass over a trial's length, not a handful of scans
    std::ifstream in(f, std::ios::binary);
    std::vector<float> v((fs::file_size(f) / 16) * 4);
    in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(v.size() * 4));
    Scan s;
    s.stamp = static_cast<StampNs>(scans.size() + 1) * 100'000'000;
    for (std::size_t i = 0; i + 3 < v.size(); i += 4) {
      s.points.emplace_back(v[i], v[i + 1], v[i + 2]);
      s.intensity.push_back(v[i + 3]);
    }
    scans.push_back(std::move(s));
  }
  return scans;
}

bool identical(const Scan& a, const Scan& b) {
  return a.stamp == b.stamp && a.size() == b.size() && a.intensity.size() == b.intensity.size() &&
         a.time.size() == b.time.size() && a.ring == b.ring &&
         std::memcmp(a.points.data(), b.points.data(), a.size() * 12) == 0 &&
         std::memcmp(a.intensity.data(), b.intensity.data(), a.intensity.size() * 4) == 0 &&
         std::memcmp(a.time.data(), b.time.data(), a.time.size() * 4) == 0;
}

void measure(const std::string& name, const std::vector<Scan>& scans, const fs::path& dir, int repeat) {
  if (scans.empty()) return;
  double points = 0;
  for (const auto& s : scans) points += static_cast<double>(s.size());
  double plain_bytes = 0, plain_read = 0;
  for (auto c : {trials::ScanCompression::None, trials::ScanCompression::Lz4}) {
    const bool lz4 = c == trials::ScanCompression::Lz4;
    const std::string path = (dir / (name + (lz4 ? "-lz4" : "-none") + ".scans")).string();
    bench::Stopwatch write;
    {
      trials::CachingScanSource caching(std::make_unique<MemorySource>(scans), path, "", c);
      for (Scan s; caching.next(s);) {}
    }
    const double write_ms = write.elapsedMs() / static_cast<double>(scans.size());
    std::vector<double> passes;
    bool same = true;
    for (int r = 0; r <= repeat; ++r) {  // pass 0 warms the page cache
      bench::Stopwatch read;
      trials::CachedScanSource cached(path);
      Scan s;
      std::size_t k = 0;
      while (cached.next(s)) {
        if (r == 0) same = same && k < scans.size() && identical(s, scans[k]);
        ++k;
      }
      if (r > 0) passes.push_back(read.elapsedMs() / static_cast<double>(scans.size()));
      same = same && k == scans.size();
    }
    const double bytes = static_cast<double>(fs::file_size(path)) / static_cast<double>(scans.size());
    const double read_ms = bench::quantile(passes, 0.5);
    if (!lz4) plain_bytes = bytes, plain_read = read_ms;
    std::printf(
        "%-28s %-5s %5zu scans %8.0f points/scan %9.0f B/scan %6.1f %%  write %6.2f ms  warm read %6.2f ms"
        "%s  %s\n",
        name.c_str(), lz4 ? "lz4" : "none", scans.size(), points / static_cast<double>(scans.size()), bytes,
        100.0 * bytes / plain_bytes, write_ms, read_ms,
        lz4 ? (" (+" + std::to_string(read_ms - plain_read).substr(0, 4) + " ms)").c_str() : "",
        same ? "bit-identical" : "DIFFERENT");
    fs::remove(path);
    fs::remove(cache::infoPathOf(path));
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string kitti, dir_arg;
  std::vector<std::string> bags;
  std::size_t max_scans = 100;
  int repeat = 5;
  CommandLine app("bench_scan_cache",
                  "Bytes per scan, write time and warm read time of the scan cache, plain and compressed.");
  app.add_option("--kitti", kitti, "a folder of KITTI velodyne .bin scans")->type_name("DIR");
  app.add_option("BAG", bags, "ROS 1 bags (BAG or BAG:TOPIC; default topic /os_cloud_node/points)");
  app.add_option("--scans", max_scans, "at most this many scans per input")->capture_default_str();
  app.add_option("--repeat", repeat, "warm read passes (the median is printed)")->capture_default_str();
  app.add_option("--dir", dir_arg, "where the cache files go (default: a folder under the temporary directory)");
  if (const std::optional<int> code = app.parseOrExit(argc, argv)) return *code;
  const fs::path dir = dir_arg.empty() ? fs::temp_directory_path() / ("bench_scan_cache_" + std::to_string(::getpid()))
                                       : fs::path(dir_arg);
  fs::create_directories(dir);
  try {
    if (!kitti.empty())
      measure("kitti:" + fs::path(kitti).parent_path().filename().string(), readKitti(kitti, max_scans), dir, repeat);
    for (const auto& arg : bags) {
      std::string bag = arg, topic = "/os_cloud_node/points";
      if (const auto colon = arg.rfind(':'); colon != std::string::npos && colon > 0 && !fs::exists(arg))
        bag = arg.substr(0, colon), topic = arg.substr(colon + 1);
      trials::Ros1ScanSource source(bag, topic);
      std::vector<Scan> scans;
      for (Scan s; scans.size() < max_scans && source.next(s);) scans.push_back(s);
      measure(fs::path(bag).filename().string(), scans, dir, repeat);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_scan_cache: %s\n", e.what());
    if (dir_arg.empty()) fs::remove_all(dir);
    return 1;
  }
  if (dir_arg.empty()) fs::remove_all(dir);
  return 0;
}
