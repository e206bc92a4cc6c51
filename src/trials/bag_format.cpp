#include "cosmo/trials/bag_format.hpp"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "cosmo/trials/ros2_bag.hpp"

namespace fs = std::filesystem;

namespace cosmo::trials {

namespace {
std::string printable(const char* bytes, std::size_t n) {
  std::string s;
  for (std::size_t i = 0; i < n; ++i) s += (bytes[i] >= 32 && bytes[i] < 127) ? bytes[i] : '.';
  return s;
}
}  // namespace

BagFormat detectBagFormat(const std::string& path) {
  if (!fs::exists(path)) throw std::runtime_error(path + ": no such bag (file or folder)");
  if (fs::is_directory(path)) {
    ros2BagFiles(path);  // throws naming the folder when it holds no .db3
    return BagFormat::Ros2Sqlite;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  char head[16] = {};
  in.read(head, sizeof head);
  const std::size_t got = static_cast<std::size_t>(in.gcount());
  if (got >= 13 && std::memcmp(head, "#ROSBAG V2.0\n", 13) == 0) return BagFormat::Ros1;
  if (got == 16 && std::memcmp(head, "SQLite format 3\0", 16) == 0) return BagFormat::Ros2Sqlite;
  if (got >= 8 && std::memcmp(head, "#ROSBAG ", 8) == 0)
    throw std::runtime_error(path + ": ROS 1 bag version '" + printable(head, 12) + "' is not supported (V2.0 only)");
  throw std::runtime_error(path +
                           ": neither a ROS 1 bag (#ROSBAG V2.0) nor a ROS 2 sqlite3 bag (.db3 or its "
                           "folder); it starts with '" +
                           printable(head, got) + "'");
}

bool ros1ChunksCompressed(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(65536, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head.find("compression=bz2") != std::string::npos || head.find("compression=lz4") != std::string::npos;
}

std::string bagFormatName(BagFormat format) { return format == BagFormat::Ros1 ? "ROS 1 bag" : "ROS 2 sqlite3 bag"; }

}  // namespace cosmo::trials
