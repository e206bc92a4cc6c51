#pragma once
// ROS 2 bags in the sqlite3 storage (rosbag2's default before Iron; CU-Multi's bags), read and written with
// libsqlite3 and no ROS 2: a folder with `metadata.yaml` and `<name>_0.db3` [, `_1.db3`, ...], or one `.db3`.
// Tables `topics(id, name, type, serialization_format, offered_qos_profiles)` and `messages(id, topic_id,
// timestamp, data)`; ROS 2 topic names have no leading slash, and a topic asked for with or without one is
// found. Errors throw std::runtime_error naming the bag (and the topics it has, when a topic is missing).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cosmo/common/time.hpp"

namespace cosmo::trials {

struct Ros2Topic {
  std::string name;
  std::string type;
  std::string serialization_format;
  std::size_t messages = 0;
};

/// The topics of a ROS 2 bag (folder or .db3), with their message counts.
std::vector<Ros2Topic> listRos2Topics(const std::string& bag_path);

/// The .db3 files of a bag, in recording order: the folder's metadata.yaml `relative_file_paths` (else its
/// *.db3 sorted by name), or the file itself. Throws for a compressed bag (`compression_format` set).
std::vector<std::string> ros2BagFiles(const std::string& bag_path);

/// The messages of one topic in receive-time order, each valid until the next call.
class Ros2BagReader {
 public:
  struct Message {
    StampNs received = 0;  ///< the bag's `timestamp` column
    const std::uint8_t* data = nullptr;
    std::size_t size = 0;
  };
  Ros2BagReader(const std::string& bag_path, const std::string& topic);
  ~Ros2BagReader();
  Ros2BagReader(const Ros2BagReader&) = delete;
  Ros2BagReader& operator=(const Ros2BagReader&) = delete;

  const Ros2Topic& topic() const;
  std::size_t size() const { return topic().messages; }
  /// "<bag> <topic>", for error messages.
  const std::string& where() const;
  /// Last receive time of the topic's messages.
  StampNs lastReceived() const;
  /// Restarts at the first message received at or after `received`.
  void seek(StampNs received);
  bool next(Message& message);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes a ROS 2 sqlite3 bag folder `<folder>/<name>_0.db3` + `metadata.yaml` (name = the folder's name).
class Ros2BagWriter {
 public:
  explicit Ros2BagWriter(const std::string& folder);
  ~Ros2BagWriter();
  Ros2BagWriter(const Ros2BagWriter&) = delete;
  Ros2BagWriter& operator=(const Ros2BagWriter&) = delete;
  /// Adds a topic (CDR serialization); returns its id for write().
  int addTopic(const std::string& name, const std::string& type);
  void write(int topic, StampNs received, const std::vector<std::uint8_t>& cdr);
  /// Commits the messages and writes metadata.yaml (also done by the destructor).
  void close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cosmo::trials
