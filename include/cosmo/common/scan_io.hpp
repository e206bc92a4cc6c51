#pragma once
// Reading and writing scan files: KITTI velodyne .bin (x y z reflectance, float32), plain xyz .bin
// (x y z, float32, e.g. gtsam_points dumps) and PCD (any PCL-readable PCD with x y z [intensity]).
// Errors throw std::runtime_error naming the file.
#include <string>
#include <vector>

#include "cosmo/common/scan.hpp"

namespace cosmo {

/// KITTI velodyne binary: 4 float32 per point (x, y, z, reflectance).
Scan readKittiBin(const std::string& path);
/// Plain binary: 3 float32 per point (x, y, z).
Scan readXyzBin(const std::string& path);
/// PCD file (ASCII/binary/compressed) with fields x y z and optionally intensity.
Scan readPcd(const std::string& path);
/// By extension: .pcd -> readPcd; .bin -> KITTI (16 bytes/point) unless the name is points.bin or the size
/// is not a multiple of 16, then xyz (12 bytes/point).
Scan readScanFile(const std::string& path);
/// Binary PCD with x y z intensity.
void writePcd(const std::string& path, const Scan& scan);
/// Scan files (.pcd, .bin) in a folder, sorted by name; a folder of sub-folders each holding one
/// points.bin / cloud.pcd (the gtsam_points dump layout) also works.
std::vector<std::string> listScanFiles(const std::string& folder);

}  // namespace cosmo
