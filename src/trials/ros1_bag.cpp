#include "cosmo/trials/ros1_bag.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "ros1_chunk.hpp"
#include "ros1_records.hpp"

namespace cosmo::trials {

using namespace ros1;

namespace {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr std::uint64_t kMagicSize = 13;
constexpr std::uint32_t kMaxConnectionHeader = 64u << 20;

std::string withoutSlash(const std::string& t) { return !t.empty() && t[0] == '/' ? t.substr(1) : t; }

/// rosbag reads a time as sec + nsec (normalised), and leaves out entries before (0 s, 1 ns).
StampNs stampOf(std::uint32_t sec, std::uint32_t nsec) { return StampNs{sec} * 1000000000ull + nsec; }

Ros1Compression compressionOf(const std::string& name, const Place& place) {
  if (name == "none") return Ros1Compression::None;
  if (name == "bz2") return Ros1Compression::Bz2;
  if (name == "lz4") return Ros1Compression::Lz4;
  fail(place, "chunk", "compression '" + name + "' is not none, bz2 or lz4");
}

void expectOp(const Record& r, std::uint8_t op, const Place& place, const char* record) {
  const std::uint8_t got = r.fields.op();
  if (got != op)
    fail(place, record,
         "op " + std::to_string(got) + " where a " + record + " record (op " + std::to_string(op) + ") belongs");
}

}  // namespace

Ros1Bag::Ros1Bag(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw std::runtime_error(path + ": cannot open: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw std::runtime_error(path + ": not a regular file");
  }
  file_size_ = static_cast<std::uint64_t>(st.st_size);
  try {
    readIndex();
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

Ros1Bag::~Ros1Bag() { ::close(fd_); }

void Ros1Bag::readIndex() {
  char magic[kMagicSize] = {};
  const Place start{&path_, 0};
  if (file_size_ < kMagicSize)
    throw Ros1BagError(path_ + ": " + std::to_string(file_size_) + " bytes: not a ROS 1 bag");
  readExactly(fd_, 0, magic, kMagicSize, start, "bag header");
  if (std::memcmp(magic, kMagic, kMagicSize) != 0)
    throw Ros1BagError(path_ + ": does not start with '#ROSBAG V2.0': not a ROS 1 bag of format 2.0");
  const Place head{&path_, kMagicSize};
  const Record header = recordInFile(fd_, file_size_, head, "bag header");
  expectOp(header, kBagHeader, head, "bag header");
  const std::uint64_t index_pos = header.fields.u64("index_pos");
  const std::uint32_t conn_count = header.fields.u32("conn_count");
  const std::uint32_t chunk_count = header.fields.u32("chunk_count");
  if (index_pos == 0) fail(head, "bag header", "index_pos is 0: the bag has no index (its recording was not closed)");
  if (index_pos == file_size_ && conn_count == 0 && chunk_count == 0) return;  // an empty index: a recording of nothing
  if (index_pos < header.end() || index_pos >= file_size_)
    fail(head, "bag header",
         "index_pos " + std::to_string(index_pos) + " lies outside the file's records (bytes " +
             std::to_string(header.end()) + " to " + std::to_string(file_size_) + "): the file is truncated");
  std::uint64_t offset = index_pos;
  for (std::uint32_t i = 0; i < conn_count; ++i) offset = readConnection(offset);
  for (std::uint32_t i = 0; i < chunk_count; ++i) offset = readChunkInfo(offset);
}

std::uint64_t Ros1Bag::readConnection(std::uint64_t offset) {
  const Place place{&path_, offset};
  const Record r = recordInFile(fd_, file_size_, place, "connection");
  expectOp(r, kConnection, place, "connection");
  Ros1Connection c;
  c.id = r.fields.u32("conn");
  c.topic = r.fields.text("topic");
  if (r.data_len > kMaxConnectionHeader)
    fail(place, "connection", "connection header of " + std::to_string(r.data_len) + " bytes");
  std::vector<std::uint8_t> data(r.data_len);
  readExactly(fd_, r.data_offset, data.data(), data.size(), place, "connection");
  Fields header;
  header.parse(data.data(), data.size(), place, "connection");
  c.type = header.text("type");
  c.md5sum = header.text("md5sum");
  c.definition = header.textOr("message_definition", "");
  if (!position_.count(c.id)) {  // a repeated id: the first one, as rosbag keeps it
    position_[c.id] = connections_.size();
    connections_.push_back(std::move(c));
    index_.emplace_back();
  }
  return r.end();
}

std::uint64_t Ros1Bag::readChunkInfo(std::uint64_t offset) {
  const Place place{&path_, offset};
  const Record r = recordInFile(fd_, file_size_, place, "chunk info");
  expectOp(r, kChunkInfo, place, "chunk info");
  const std::uint32_t ver = r.fields.u32("ver");
  if (ver != 1) fail(place, "chunk info", "version " + std::to_string(ver) + " (1 expected)");
  const std::uint64_t chunk_pos = r.fields.u64("chunk_pos");
  const std::uint32_t count = r.fields.u32("count");
  if (std::uint64_t{count} * 8 != r.data_len)
    fail(place, "chunk info",
         "field 'count' says " + std::to_string(count) + " connections (" + std::to_string(std::uint64_t{count} * 8) +
             " bytes), the record holds " + std::to_string(r.data_len) + " bytes");
  std::vector<std::uint8_t> data(r.data_len);
  readExactly(fd_, r.data_offset, data.data(), data.size(), place, "chunk info");
  std::map<std::uint32_t, std::uint32_t> counts;
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t conn = le32(&data[8 * i]), n = le32(&data[8 * i + 4]);
    if (!position_.count(conn))
      fail(place, "chunk info",
           "entry " + std::to_string(i) + " names connection " + std::to_string(conn) + ", which the bag's " +
               std::to_string(connections_.size()) + " connection records do not define");
    if (!counts.emplace(conn, n).second)
      fail(place, "chunk info", "connection " + std::to_string(conn) + " listed twice");
  }
  if (chunk_pos < kMagicSize || chunk_pos >= file_size_)
    fail(
        place, "chunk info",
        "chunk_pos " + std::to_string(chunk_pos) + " lies outside the file (" + std::to_string(file_size_) + " bytes)");
  Ros1Chunk chunk;
  chunk.pos = chunk_pos;
  chunks_.push_back(chunk);
  readChunkIndex(counts);
  return r.end();
}

/// The chunk record at the last chunk info's chunk_pos and the index data records that follow its data, one per
/// connection of the chunk info, with the message counts it gives.
void Ros1Bag::readChunkIndex(const std::map<std::uint32_t, std::uint32_t>& counts) {
  Ros1Chunk& chunk = chunks_.back();
  const auto chunk_number = static_cast<std::uint32_t>(chunks_.size() - 1);
  const Place place{&path_, chunk.pos};
  const Record r = recordInFile(fd_, file_size_, place, "chunk");
  expectOp(r, kChunk, place, "chunk");
  chunk.compression = compressionOf(r.fields.text("compression"), place);
  chunk.size = r.fields.u32("size");
  chunk.data_pos = r.data_offset;
  chunk.data_size = r.data_len;
  if (chunk.compression == Ros1Compression::None && chunk.size != chunk.data_size)
    fail(place, "chunk",
         "uncompressed chunk of " + std::to_string(chunk.data_size) + " bytes whose field 'size' says " +
             std::to_string(chunk.size));
  if (chunk.size > kRos1MaxChunkBytes)
    fail(place, "chunk",
         "field 'size' says " + std::to_string(chunk.size) + " bytes, more than this reader accepts (" +
             std::to_string(kRos1MaxChunkBytes) + ")");
  std::uint64_t offset = r.end();
  std::map<std::uint32_t, bool> seen;
  for (std::size_t k = 0; k < counts.size(); ++k) {
    const Place at{&path_, offset};
    const Record ix = recordInFile(fd_, file_size_, at, "index data");
    expectOp(ix, kIndexData, at, "index data");
    const std::uint32_t ver = ix.fields.u32("ver"), conn = ix.fields.u32("conn"), n = ix.fields.u32("count");
    if (ver != 1) fail(at, "index data", "version " + std::to_string(ver) + " (1 expected)");
    const auto expected = counts.find(conn);
    if (expected == counts.end() || seen[conn])
      fail(at, "index data",
           "connection " + std::to_string(conn) + " is not one of the chunk info's (at chunk_pos " +
               std::to_string(chunk.pos) + ") or is indexed twice");
    seen[conn] = true;
    if (n != expected->second || std::uint64_t{n} * 12 != ix.data_len)
      fail(at, "index data",
           "field 'count' says " + std::to_string(n) + " messages in " + std::to_string(ix.data_len) +
               " bytes; the chunk info says " + std::to_string(expected->second) + " (12 bytes each)");
    std::vector<std::uint8_t> data(ix.data_len);
    readExactly(fd_, ix.data_offset, data.data(), data.size(), at, "index data");
    auto& list = index_[position_.at(conn)];
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint8_t* e = &data[12 * std::size_t{i}];
      Ros1MessageRef m;
      m.received = stampOf(le32(e), le32(e + 4));
      m.connection = conn;
      m.chunk = chunk_number;
      m.offset = le32(e + 8);
      if (m.offset >= chunk.size)
        fail(at, "index data",
             "entry " + std::to_string(i) + ": offset " + std::to_string(m.offset) + " lies outside the chunk's " +
                 std::to_string(chunk.size) + " bytes");
      if (m.received != 0) list.push_back(m);
    }
    offset = ix.end();
  }
}

const Ros1Connection& Ros1Bag::connection(std::uint32_t id) const {
  const auto it = position_.find(id);
  if (it == position_.end()) throw Ros1BagError(path_ + ": no connection " + std::to_string(id));
  return connections_[it->second];
}

std::vector<std::uint32_t> Ros1Bag::topicConnections(const std::string& topic) const {
  std::vector<std::uint32_t> ids;
  for (const auto& c : connections_)
    if (withoutSlash(c.topic) == withoutSlash(topic)) ids.push_back(c.id);
  return ids;
}

std::string Ros1Bag::describeTopics() const {
  std::string topics;
  for (const auto& c : connections_) {
    const std::string entry = c.topic + " (" + c.type + ")";
    if (topics.find(entry) == std::string::npos) topics += (topics.empty() ? "" : ", ") + entry;
  }
  return topics.empty() ? "none" : topics;
}

std::vector<Ros1MessageRef> Ros1Bag::messages(const std::vector<std::uint32_t>& connection_ids) const {
  // rosbag::View's merge, step by step, so that ties between connections come out as rosbag gives them: one range
  // per connection in id order, each in index order (stable by time, as rosbag's multiset); the next message is
  // the last of the ranges sorted by descending time with std::sort, as rosbag::View::iterator does.
  std::vector<std::vector<Ros1MessageRef>> ranges;
  std::size_t total = 0;
  for (const auto& [id, pos] : position_)
    if (std::find(connection_ids.begin(), connection_ids.end(), id) != connection_ids.end() && !index_[pos].empty()) {
      ranges.push_back(index_[pos]);
      std::stable_sort(ranges.back().begin(), ranges.back().end(),
                       [](const Ros1MessageRef& a, const Ros1MessageRef& b) { return a.received < b.received; });
      total += ranges.back().size();
    }
  struct Cursor {
    std::size_t range, pos;
  };
  std::vector<Cursor> cursors;
  for (std::size_t r = 0; r < ranges.size(); ++r) cursors.push_back({r, 0});
  auto later = [&](const Cursor& a, const Cursor& b) {
    return ranges[a.range][a.pos].received > ranges[b.range][b.pos].received;
  };
  std::sort(cursors.begin(), cursors.end(), later);
  std::vector<Ros1MessageRef> out;
  out.reserve(total);
  while (!cursors.empty()) {
    Cursor& c = cursors.back();
    out.push_back(ranges[c.range][c.pos]);
    if (++c.pos == ranges[c.range].size()) cursors.pop_back();
    std::sort(cursors.begin(), cursors.end(), later);
  }
  return out;
}

void Ros1Bag::readChunk(std::size_t i, std::vector<std::uint8_t>& out) const {
  const Ros1Chunk& c = chunks_.at(i);
  const Place place{&path_, c.pos};
  if (c.compression == Ros1Compression::None) {
    out.resize(c.size);
    readExactly(fd_, c.data_pos, out.data(), c.size, place, "chunk");
    return;
  }
  thread_local std::vector<std::uint8_t> stored;
  stored.resize(c.data_size);
  readExactly(fd_, c.data_pos, stored.data(), c.data_size, place, "chunk");
  decompressChunk(c.compression, stored.data(), stored.size(), c.size, out, place);
}

Ros1Bag::Bytes Ros1Bag::messageData(const Ros1MessageRef& m, const std::vector<std::uint8_t>& chunk) const {
  Place place{&path_, m.offset, true, chunks_.at(m.chunk).pos};
  for (;;) {
    const Record r = recordIn(chunk.data(), chunk.size(), place, "message data");
    const std::uint8_t op = r.fields.op();
    if (op == kConnection || op == kMessageDefinition) {  // rosbag skips these to the message
      place.offset = r.end();
      continue;
    }
    if (op != kMessageData)
      fail(place, "message data", "op " + std::to_string(op) + " where the index points at a message (op 2)");
    const std::uint32_t conn = r.fields.u32("conn");
    if (conn != m.connection)
      fail(place, "message data",
           "connection " + std::to_string(conn) + " where the index says " + std::to_string(m.connection));
    return {chunk.data() + r.data_offset, r.data_len};
  }
}

}  // namespace cosmo::trials
