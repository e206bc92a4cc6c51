#include "cosmo/common/scan_io.hpp"

#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace cosmo {
namespace fs = std::filesystem;

namespace {
std::vector<float> readFloats(const std::string& path, std::size_t per_point) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  in.seekg(0, std::ios::end);
  const auto bytes = static_cast<std::size_t>(in.tellg());
  in.seekg(0);
  if (bytes % (per_point * sizeof(float)) != 0)
    throw std::runtime_error(path + ": size " + std::to_string(bytes) + " bytes is not a multiple of " +
                             std::to_string(per_point * sizeof(float)) + " (" + std::to_string(per_point) +
                             " float32 per point)");
  std::vector<float> data(bytes / sizeof(float));
  in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(bytes));
  if (!in) throw std::runtime_error(path + ": short read");
  return data;
}
}  // namespace

Scan readKittiBin(const std::string& path) {
  const auto d = readFloats(path, 4);
  Scan s;
  s.points.reserve(d.size() / 4);
  s.intensity.reserve(d.size() / 4);
  for (std::size_t i = 0; i + 3 < d.size(); i += 4) {
    s.points.emplace_back(d[i], d[i + 1], d[i + 2]);
    s.intensity.push_back(d[i + 3]);
  }
  return s;
}

Scan readXyzBin(const std::string& path) {
  const auto d = readFloats(path, 3);
  Scan s;
  s.points.reserve(d.size() / 3);
  for (std::size_t i = 0; i + 2 < d.size(); i += 3) s.points.emplace_back(d[i], d[i + 1], d[i + 2]);
  return s;
}

Scan readPcd(const std::string& path) {
  pcl::PCLPointCloud2 blob;
  pcl::PCDReader reader;
  if (reader.read(path, blob) < 0) throw std::runtime_error(path + ": not a readable PCD file");
  bool has_intensity = false;
  for (const auto& f : blob.fields) has_intensity |= (f.name == "intensity");
  pcl::PointCloud<pcl::PointXYZI> cloud;
  pcl::fromPCLPointCloud2(blob, cloud);
  Scan s;
  s.points.reserve(cloud.size());
  for (const auto& p : cloud.points) {
    s.points.emplace_back(p.x, p.y, p.z);
    if (has_intensity) s.intensity.push_back(p.intensity);
  }
  return s;
}

Scan readScanFile(const std::string& path) {
  const fs::path p(path);
  const std::string ext = p.extension().string();
  if (ext == ".pcd") return readPcd(path);
  if (ext == ".bin") {
    std::error_code ec;
    const auto bytes = fs::file_size(p, ec);
    if (ec) throw std::runtime_error(path + ": cannot open");
    if (p.filename() == "points.bin" || bytes % 16 != 0) return readXyzBin(path);
    return readKittiBin(path);
  }
  throw std::runtime_error(path + ": unknown scan file type '" + ext + "' (expected .pcd or .bin)");
}

void writePcd(const std::string& path, const Scan& scan) {
  pcl::PointCloud<pcl::PointXYZI> cloud;
  cloud.reserve(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i) {
    pcl::PointXYZI q;
    q.x = scan.points[i].x();
    q.y = scan.points[i].y();
    q.z = scan.points[i].z();
    q.intensity = scan.hasIntensity() ? scan.intensity[i] : 0.0f;
    cloud.push_back(q);
  }
  if (pcl::io::savePCDFileBinary(path, cloud) < 0) throw std::runtime_error(path + ": cannot write PCD");
}

std::vector<std::string> listScanFiles(const std::string& folder) {
  if (!fs::is_directory(folder)) throw std::runtime_error(folder + ": not a folder");
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(folder)) {
    if (e.is_regular_file()) {
      const auto ext = e.path().extension().string();
      if (ext == ".pcd" || ext == ".bin") files.push_back(e.path().string());
    } else if (e.is_directory()) {
      for (const char* name : {"points.bin", "cloud.pcd"})
        if (fs::exists(e.path() / name)) files.push_back((e.path() / name).string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace cosmo
