// ROS 2 sqlite3 bags as the trials read them: the bag folder's metadata.yaml and its .db3 (topics, messages),
// every topic listed, every PointCloud2 topic read as scans and its span. The input is the metadata.yaml text
// followed by the .db3 bytes (from the sqlite header "SQLite format 3" on); without the header, the whole input
// is the .db3. The folder and file are named as CU-Multi's robot 1 bag (what the seed's metadata.yaml lists).
#include <algorithm>
#include <cstring>
#include <filesystem>

#include "../fuzz_target.hpp"
#include "../input_file.hpp"
#include "cosmo/trials/ros2_bag.hpp"
#include "cosmo/trials/trial_scans.hpp"

using namespace cosmo;

COSMO_FUZZ_TARGET(ros2_bag) {
  static const char kSqlite[] = "SQLite format 3";
  const std::uint8_t* header = std::search(data, data + size, kSqlite, kSqlite + sizeof kSqlite);
  const bool split = header != data + size;
  const std::uint8_t* db3 = split ? header : data;
  const std::filesystem::path folder = fuzz::scratchDir() / "robot1_walk_a_lidar";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  fuzz::inputFile(db3, static_cast<std::size_t>(data + size - db3), "robot1_walk_a_lidar/robot1_walk_a_lidar_0.db3");
  if (split && header > data)
    fuzz::inputFile(data, static_cast<std::size_t>(header - data), "robot1_walk_a_lidar/metadata.yaml");
  const std::string path = folder.string();
  for (const auto& t : trials::listRos2Topics(path)) {
    if (t.type != "sensor_msgs/msg/PointCloud2") continue;
    try {
      trials::Ros2ScanSource source(path, t.name, false);
      Scan scan;
      while (source.next(scan)) {}
      trials::readRos2TrialSpan(path, t.name, 'a');
    } catch (const std::runtime_error&) {  // a bad topic; the others still read
    }
  }
}
