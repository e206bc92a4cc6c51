#include "ros1_records.hpp"

#include <unistd.h>

#include <cerrno>

namespace cosmo::trials::ros1 {

namespace {

/// Record headers hold a few fields and, for connections, a message definition (a few kB).
constexpr std::uint32_t kMaxHeaderBytes = 64u << 20;

/// What to do about a damaged record: the index can be rebuilt from the chunks; damaged chunks cannot.
std::string advice(const char* record, const std::string& file) {
  const std::string r = record;
  if (r == "bag header" || r == "connection" || r == "chunk info" || r == "index data")
    return "the bag's index is damaged: `rosbag reindex " + file + "` rebuilds it from the chunks (`rosbag check " +
           file + "` tells more)";
  return "the bag's data is damaged: `rosbag check " + file +
         "` confirms it; copy or download the file again (`rosbag reindex` rebuilds only the index)";
}

}  // namespace

std::string Place::describe(const char* record) const {
  std::string s = (file ? *file : std::string("<bag>")) + ": " + record + " record at byte " + std::to_string(offset);
  if (in_chunk) s += " of the decompressed chunk at byte " + std::to_string(chunk);
  return s;
}

void fail(const Place& place, const char* record, const std::string& why) {
  throw Ros1BagError(place.describe(record) + ": " + why + "; " + advice(record, place.file ? *place.file : ""));
}

void Fields::parse(const std::uint8_t* data, std::size_t size, const Place& place, const char* record) {
  place_ = place;
  record_ = record;
  fields_.clear();
  std::size_t pos = 0;
  while (pos < size) {
    if (size - pos < 4) fail(place, record, "header ends inside a field length");
    const std::uint32_t len = le32(data + pos);
    pos += 4;
    if (len > size - pos)
      fail(place, record,
           "header field of " + std::to_string(len) + " bytes runs past the header (" + std::to_string(size - pos) +
               " bytes left)");
    const char* f = reinterpret_cast<const char*>(data + pos);
    const void* eq = std::memchr(f, '=', len);
    if (!eq) fail(place, record, "header field without '='");
    const std::size_t name_len = static_cast<std::size_t>(static_cast<const char*>(eq) - f);
    std::string name(f, name_len), value(f + name_len + 1, len - name_len - 1);
    bool replaced = false;
    for (auto& [n, v] : fields_)
      if (n == name) {
        v = value;
        replaced = true;
      }
    if (!replaced) fields_.emplace_back(std::move(name), std::move(value));
    pos += len;
  }
}

const std::string* Fields::find(const char* name) const {
  for (const auto& [n, v] : fields_)
    if (n == name) return &v;
  return nullptr;
}

const std::string& Fields::required(const char* name, std::size_t size) const {
  const std::string* v = find(name);
  if (!v) fail(place_, record_, std::string("field '") + name + "' missing");
  if (size != 0 && v->size() != size)
    fail(place_, record_,
         std::string("field '") + name + "' has " + std::to_string(v->size()) + " bytes, expected " +
             std::to_string(size));
  return *v;
}

std::uint8_t Fields::op() const { return static_cast<std::uint8_t>(required("op", 1)[0]); }

std::uint32_t Fields::u32(const char* name) const {
  std::uint32_t v;
  std::memcpy(&v, required(name, 4).data(), 4);
  return v;
}

std::uint64_t Fields::u64(const char* name) const {
  std::uint64_t v;
  std::memcpy(&v, required(name, 8).data(), 8);
  return v;
}

std::string Fields::text(const char* name) const { return required(name, 0); }

std::string Fields::textOr(const char* name, const std::string& fallback) const {
  const std::string* v = find(name);
  return v ? *v : fallback;
}

Record recordIn(const std::uint8_t* bytes, std::size_t size, const Place& place, const char* record) {
  const std::uint64_t at = place.offset;
  if (at > size || size - at < 4)
    fail(place, record,
         "the record's header length lies past the end of the data (" + std::to_string(size) + " bytes)");
  const std::uint32_t header_len = le32(bytes + at);
  if (header_len > size - at - 4)
    fail(place, record,
         "header of " + std::to_string(header_len) + " bytes runs past the end of the data (" +
             std::to_string(size - at - 4) + " bytes left)");
  Record r;
  r.fields.parse(bytes + at + 4, header_len, place, record);
  const std::uint64_t len_at = at + 4 + header_len;
  if (size - len_at < 4) fail(place, record, "the data length lies past the end of the data");
  r.data_len = le32(bytes + len_at);
  r.data_offset = len_at + 4;
  if (r.data_len > size - r.data_offset)
    fail(place, record,
         "data of " + std::to_string(r.data_len) + " bytes runs past the end of the data (" +
             std::to_string(size - r.data_offset) + " bytes left)");
  return r;
}

void readExactly(int fd, std::uint64_t offset, void* out, std::size_t n, const Place& place, const char* record) {
  auto* p = static_cast<std::uint8_t*>(out);
  while (n > 0) {
    const ssize_t got = ::pread(fd, p, n, static_cast<off_t>(offset));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) fail(place, record, std::string("cannot read: ") + std::strerror(errno));
    if (got == 0) fail(place, record, "the file ends at byte " + std::to_string(offset) + " (truncated)");
    p += got;
    offset += static_cast<std::uint64_t>(got);
    n -= static_cast<std::size_t>(got);
  }
}

Record recordInFile(int fd, std::uint64_t file_size, const Place& place, const char* record) {
  const std::uint64_t at = place.offset;
  if (at > file_size || file_size - at < 4)
    fail(place, record,
         "the record lies past the end of the file (" + std::to_string(file_size) + " bytes): the file is truncated");
  std::uint8_t len[4];
  readExactly(fd, at, len, 4, place, record);
  const std::uint32_t header_len = le32(len);
  if (header_len > file_size - at - 4)
    fail(place, record,
         "header of " + std::to_string(header_len) + " bytes runs past the end of the file (" +
             std::to_string(file_size - at - 4) + " bytes left)");
  if (header_len > kMaxHeaderBytes)
    fail(place, record, "header of " + std::to_string(header_len) + " bytes, more than any real record header");
  if (file_size - at - 4 - header_len < 4) fail(place, record, "the data length lies past the end of the file");
  std::vector<std::uint8_t> header(header_len + std::size_t{4});  // the header and the data length
  readExactly(fd, at + 4, header.data(), header.size(), place, record);
  Record r;
  r.fields.parse(header.data(), header_len, place, record);
  r.data_len = le32(header.data() + header_len);
  r.data_offset = at + 8 + header_len;
  if (r.data_len > file_size - r.data_offset)
    fail(place, record,
         "data of " + std::to_string(r.data_len) + " bytes runs past the end of the file (" +
             std::to_string(file_size - r.data_offset) + " bytes left): the file is truncated or the record damaged");
  return r;
}

}  // namespace cosmo::trials::ros1
