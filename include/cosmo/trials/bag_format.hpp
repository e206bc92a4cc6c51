#pragma once
// Which container a trial's `bag:` names, told by content, not by name: a ROS 1 bag starts with
// "#ROSBAG V2.0", a ROS 2 sqlite3 bag is a folder of .db3 files (with metadata.yaml) or one .db3 whose
// first bytes are the sqlite header "SQLite format 3". Anything else throws naming the file.
#include <string>

namespace cosmo::trials {

enum class BagFormat { Ros1, Ros2Sqlite };

BagFormat detectBagFormat(const std::string& path);
std::string bagFormatName(BagFormat format);  ///< "ROS 1 bag", "ROS 2 sqlite3 bag"

}  // namespace cosmo::trials
