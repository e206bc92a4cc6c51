#pragma once
// The record framing of ROS 1 bags (format 2.0), bounds-checked: a record is `header_len` (uint32), a header
// of fields (`field_len` uint32, then `name=value`), `data_len` (uint32) and the data. Used by ros1_bag.cpp on the
// file and on decompressed chunks; every error is a Ros1BagError naming the file, the byte offset, the record
// and the field.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cosmo/common/byte_cursor.hpp"
#include "cosmo/trials/ros1_bag.hpp"

namespace cosmo::trials::ros1 {

/// Record ops (the `op` field).
enum Op : std::uint8_t {
  kMessageDefinition = 0x01,  ///< format 1.2; skipped inside chunks, as rosbag does
  kMessageData = 0x02,
  kBagHeader = 0x03,
  kIndexData = 0x04,
  kChunk = 0x05,
  kChunkInfo = 0x06,
  kConnection = 0x07,
};

/// Where a record lies: in the file, or inside the decompressed data of the chunk at file offset `chunk`.
struct Place {
  const std::string* file = nullptr;
  std::uint64_t offset = 0;  ///< of the record (in the file, or in the chunk's decompressed data)
  bool in_chunk = false;
  std::uint64_t chunk = 0;  ///< file offset of the chunk record
  /// "<file>: <record> record at byte N" (+ " of the decompressed chunk at byte M").
  std::string describe(const char* record) const;
};

/// Throws Ros1BagError: "<place>: <why>; <what to do>".
[[noreturn]] void fail(const Place& place, const char* record, const std::string& why);

/// The fields of one record header (`name=value`; a repeated name: the last one, as rosbag reads it).
class Fields {
 public:
  /// Parses `size` bytes of fields; throws when a field's length runs past the header or it has no '='.
  void parse(const std::uint8_t* data, std::size_t size, const Place& place, const char* record);
  bool has(const char* name) const { return find(name) != nullptr; }
  std::uint8_t op() const;  ///< throws when `op` is missing or not one byte
  std::uint32_t u32(const char* name) const;
  std::uint64_t u64(const char* name) const;
  std::string text(const char* name) const;  ///< a required string field
  std::string textOr(const char* name, const std::string& fallback) const;
  const std::vector<std::pair<std::string, std::string>>& all() const { return fields_; }

 private:
  const std::string* find(const char* name) const;
  const std::string& required(const char* name, std::size_t size) const;

  std::vector<std::pair<std::string, std::string>> fields_;
  Place place_;
  const char* record_ = "";
};

/// One record: its header fields and where its data lies (same coordinates as the record's offset).
struct Record {
  Fields fields;
  std::uint64_t data_offset = 0;
  std::uint32_t data_len = 0;
  std::uint64_t end() const { return data_offset + data_len; }
};

/// The record at `place.offset` of `bytes[0, size)` (a decompressed chunk). Throws when its header or its data
/// runs past `size`.
Record recordIn(const std::uint8_t* bytes, std::size_t size, const Place& place, const char* record);

/// The record at `place.offset` of the open file `fd` of `file_size` bytes (its header read, its data not).
/// Throws when its header or its data runs past the end of the file.
Record recordInFile(int fd, std::uint64_t file_size, const Place& place, const char* record);

/// Reads exactly `n` bytes at `offset` of `fd`; throws naming the place when the file ends first.
void readExactly(int fd, std::uint64_t offset, void* out, std::size_t n, const Place& place, const char* record);

}  // namespace cosmo::trials::ros1
