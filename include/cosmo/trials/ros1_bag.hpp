#pragma once
// ROS 1 bags (format 2.0: MCD's and cosmo's own trials, Nebula's pose-graph bags) read without ROS and with every
// length, offset and count checked against the bytes it claims: a damaged bag — a bad record, chunk or index, a
// truncated file — throws Ros1BagError naming the file, the byte offset, the record and the field, and what to
// do (`rosbag reindex` for the index, `rosbag check` and a fresh copy for damaged data); nothing reads outside
// what was read from the file. Chunks: none, bz2 (libbz2) or lz4 (liblz4's frame format, which roslz4 writes).
//
// Messages come in rosbag's order (what rosbag::View gives for the same connections: by receive time, ties as
// its merge of the connections' indexes leaves them); index entries at time 0 are left out, as rosbag does.
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosmo/common/time.hpp"

namespace cosmo::trials {

/// A bag that does not follow the format. what(): "<file>: <record> record at byte N: <problem>; <what to do>".
class Ros1BagError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Ros1Connection {
  std::uint32_t id = 0;
  std::string topic;  ///< as recorded (usually with its leading slash)
  std::string type;   ///< "sensor_msgs/PointCloud2"
  std::string md5sum;
  std::string definition;  ///< message_definition
};

enum class Ros1Compression { None, Bz2, Lz4 };

struct Ros1Chunk {
  std::uint64_t pos = 0;        ///< file offset of the chunk record
  std::uint64_t data_pos = 0;   ///< file offset of its (compressed) data
  std::uint32_t data_size = 0;  ///< bytes stored
  std::uint32_t size = 0;       ///< bytes once decompressed
  Ros1Compression compression = Ros1Compression::None;
};

/// One indexed message.
struct Ros1MessageRef {
  StampNs received = 0;  ///< the index's time (the message record's receive time)
  std::uint32_t connection = 0;
  std::uint32_t chunk = 0;   ///< index into Ros1Bag::chunks()
  std::uint32_t offset = 0;  ///< of its record in the chunk's decompressed data
};

/// The largest decompressed chunk accepted (rosbag writes 768 kB chunks, or one message when it is larger).
inline constexpr std::uint32_t kRos1MaxChunkBytes = 1u << 30;

class Ros1Bag {
 public:
  /// Opens `path` and reads and checks its header, connections, chunk infos and every chunk's index.
  explicit Ros1Bag(const std::string& path);
  ~Ros1Bag();
  Ros1Bag(const Ros1Bag&) = delete;
  Ros1Bag& operator=(const Ros1Bag&) = delete;

  const std::string& path() const { return path_; }
  const std::vector<Ros1Connection>& connections() const { return connections_; }
  const Ros1Connection& connection(std::uint32_t id) const;  ///< throws for an unknown id
  const std::vector<Ros1Chunk>& chunks() const { return chunks_; }
  /// Ids of the connections whose topic is `topic`, with or without its leading slash.
  std::vector<std::uint32_t> topicConnections(const std::string& topic) const;
  /// "topic (type), ..." of every topic (for a message naming what the bag has).
  std::string describeTopics() const;
  /// The messages of these connections in rosbag's order.
  std::vector<Ros1MessageRef> messages(const std::vector<std::uint32_t>& connection_ids) const;

  /// The decompressed data of chunk `i` (thread-safe: positioned reads). `out` is resized to the chunk's size.
  void readChunk(std::size_t i, std::vector<std::uint8_t>& out) const;
  /// A message's serialized bytes inside its chunk's decompressed data (`chunk` from readChunk); checks the
  /// record at its offset (a message data record of its connection, its data inside the chunk).
  struct Bytes {
    const std::uint8_t* data = nullptr;
    std::size_t size = 0;
  };
  Bytes messageData(const Ros1MessageRef& m, const std::vector<std::uint8_t>& chunk) const;

 private:
  void readIndex();
  std::uint64_t readConnection(std::uint64_t offset);
  std::uint64_t readChunkInfo(std::uint64_t offset);
  void readChunkIndex(const std::map<std::uint32_t, std::uint32_t>& counts);

  std::string path_;
  int fd_ = -1;
  std::uint64_t file_size_ = 0;
  std::vector<Ros1Connection> connections_;         ///< in the order of the index section
  std::map<std::uint32_t, std::size_t> position_;   ///< connection id -> its place in connections_
  std::vector<Ros1Chunk> chunks_;                    ///< in the order of the chunk infos
  std::vector<std::vector<Ros1MessageRef>> index_;  ///< per connection (same order as connections_)
};

}  // namespace cosmo::trials
