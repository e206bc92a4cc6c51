#include "cosmo/dataset/measurement_journal.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cosmo/common/byte_cursor.hpp"
#include "cosmo/common/whole_file.hpp"
#include "cosmo/jrl/dataset.hpp"

namespace cosmo::dataset {

namespace {

constexpr char kMagic[8] = {'C', 'O', 'S', 'M', 'O', 'J', 'N', 'L'};
constexpr std::uint32_t kVersion = 1;
constexpr std::uint32_t kMaxRecord = 4096;  // bytes of one record's payload (a keyframe is 233)
constexpr std::uint32_t kMaxHeader = 1 << 16;
enum Kind : std::uint8_t { kKeyframe = 1, kLoopClosure = 2, kSession = 3, kDone = 4 };

std::uint32_t crc32Of(std::string_view bytes) {
  return static_cast<std::uint32_t>(
      crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())));
}

// ---- encoding
struct Writer {
  std::string out;
  void u8(std::uint8_t v) { out.push_back(static_cast<char>(v)); }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
  }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
  }
  void f64(double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    u64(bits);
  }
  void str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    out += s;
  }
  void pose(const Pose3& T) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) f64(T.linear()(r, c));
    for (int i = 0; i < 3; ++i) f64(T.translation()(i));
  }
};

// ---- decoding: every read is bounds-checked (common/byte_cursor.hpp); a short read throws std::out_of_range
struct JournalFail {
  [[noreturn]] void operator()(const char* /*what*/, const std::string& why, std::size_t /*at*/) const {
    throw std::out_of_range(why);
  }
};

struct Reader {
  explicit Reader(std::string_view bytes)
      : in(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), JournalFail{}, 0, "cut short") {}
  ByteCursor<JournalFail> in;

  std::size_t at() const { return in.offset(); }
  std::size_t left() const { return in.left(); }
  std::string_view take(std::size_t n) { return {reinterpret_cast<const char*>(in.bytes(n, "bytes")), n}; }
  std::uint8_t u8() { return in.value<std::uint8_t>("u8"); }
  std::uint32_t u32() { return in.value<std::uint32_t>("u32"); }
  std::uint64_t u64() { return in.value<std::uint64_t>("u64"); }
  double f64() { return in.value<double>("f64"); }
  std::string str(std::size_t max) {
    const std::uint32_t n = u32();
    if (n > max) throw std::out_of_range("string of " + std::to_string(n) + " bytes");
    return std::string(take(n));
  }
  Pose3 pose() {
    Pose3 T = Pose3::Identity();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) T.matrix()(r, c) = f64();
    for (int i = 0; i < 3; ++i) T.matrix()(i, 3) = f64();
    return T;
  }
};

std::string frame(const std::string& payload) {
  Writer w;
  w.u32(static_cast<std::uint32_t>(payload.size()));
  w.u32(crc32Of(payload));
  return w.out + payload;
}

std::string markRecord(Kind kind) {
  Writer w;
  w.u8(kind);
  return frame(w.out);
}

/// One record's payload: its kind, and the measurement when it is one.
std::uint8_t decodeRecord(std::string_view payload, MeasurementRecord& out) {
  Reader r(payload);
  const std::uint8_t kind = r.u8();
  if (kind == kSession || kind == kDone) {
    if (r.left() != 0) throw std::out_of_range(std::to_string(r.left()) + " bytes left over");
    return kind;
  }
  if (kind != kKeyframe && kind != kLoopClosure) throw std::out_of_range("unknown kind " + std::to_string(kind));
  out.robot = static_cast<char>(r.u8());
  out.seq = r.u64();
  if (kind == kKeyframe) {
    KeyframeMeasurement k;
    k.robot = out.robot;
    k.index = r.u32();
    k.stamp = r.u64();
    k.odometry = r.pose();
    if (r.u8()) k.reference = r.pose();
    const bool bridged = r.u8() != 0;
    const std::uint32_t from = r.u32();
    if (bridged) k.bridge_from = from;
    k.scans_skipped = r.u32();
    out.what = k;
  } else {
    LoopClosureMeasurement lc;
    lc.owner = static_cast<char>(r.u8());
    lc.key1 = r.u64();
    lc.key2 = r.u64();
    lc.computed_at = r.u64();
    lc.measurement = r.pose();
    out.what = lc;
  }
  if (r.left() != 0) throw std::out_of_range(std::to_string(r.left()) + " bytes left over");
  return kind;
}

std::string systemError(const std::string& what, const std::string& path) {
  return what + " " + path + ": " + std::strerror(errno);
}

std::string fileNameSafe(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return s.empty() ? "unnamed" : s;
}

}  // namespace

std::string encodeJournalHeader(const JournalHeader& h) {
  Writer body;
  body.str(h.run_id);
  body.str(h.name);
  body.str(std::string(h.robots.begin(), h.robots.end()));
  body.u8(h.with_player ? 1 : 0);
  Writer w;
  w.out.append(kMagic, sizeof kMagic);
  w.u32(kVersion);
  w.u32(static_cast<std::uint32_t>(body.out.size()));
  w.out += body.out;
  w.u32(crc32Of(body.out));
  return w.out;
}

std::string encodeJournalRecord(const MeasurementRecord& record) {
  Writer w;
  if (const KeyframeMeasurement* k = record.keyframe()) {
    w.u8(kKeyframe);
    w.u8(static_cast<std::uint8_t>(record.robot));
    w.u64(record.seq);
    w.u32(k->index);
    w.u64(k->stamp);
    w.pose(k->odometry);
    w.u8(k->reference ? 1 : 0);
    if (k->reference) w.pose(*k->reference);
    w.u8(k->bridge_from ? 1 : 0);
    w.u32(k->bridge_from.value_or(0));
    w.u32(k->scans_skipped);
  } else {
    const LoopClosureMeasurement& lc = *record.loopClosure();
    w.u8(kLoopClosure);
    w.u8(static_cast<std::uint8_t>(record.robot));
    w.u64(record.seq);
    w.u8(static_cast<std::uint8_t>(lc.owner));
    w.u64(lc.key1);
    w.u64(lc.key2);
    w.u64(lc.computed_at);
    w.pose(lc.measurement);
  }
  return frame(w.out);
}

JournalContents parseJournal(std::string_view bytes, const std::string& source) {
  JournalContents c;
  c.file_bytes = bytes.size();
  Reader r(bytes);
  try {
    if (r.take(sizeof kMagic) != std::string_view(kMagic, sizeof kMagic))
      throw std::runtime_error("not a cosmo journal (no COSMOJNL magic)");
    const std::uint32_t version = r.u32();
    if (version != kVersion)
      throw std::runtime_error("journal format version " + std::to_string(version) + ", this build reads " +
                               std::to_string(kVersion));
    const std::uint32_t n = r.u32();
    if (n > kMaxHeader) throw std::runtime_error("header of " + std::to_string(n) + " bytes");
    const std::string_view body = r.take(n);
    if (r.u32() != crc32Of(body)) throw std::runtime_error("header CRC mismatch");
    Reader h(body);
    c.header.run_id = h.str(n);
    c.header.name = h.str(n);
    const std::string robots = h.str(n);
    c.header.robots.assign(robots.begin(), robots.end());
    c.header.with_player = h.u8() != 0;
    if (h.left() != 0) throw std::runtime_error("header has " + std::to_string(h.left()) + " bytes left over");
  } catch (const std::out_of_range&) {
    throw std::runtime_error(source + ": journal header cut short (" + std::to_string(bytes.size()) + " bytes)");
  } catch (const std::runtime_error& e) { throw std::runtime_error(source + ": " + e.what()); }
  c.valid_bytes = r.at();
  while (r.left() != 0) {
    const std::size_t start = r.at();
    try {
      const std::uint32_t n = r.u32();
      const std::uint32_t crc = r.u32();
      if (n == 0 || n > kMaxRecord) throw std::out_of_range("record length " + std::to_string(n));
      const std::string_view payload = r.take(n);
      if (crc32Of(payload) != crc) throw std::out_of_range("CRC mismatch");
      MeasurementRecord rec;
      const std::uint8_t kind = decodeRecord(payload, rec);
      if (kind == kSession)
        ++c.sessions;
      else if (kind == kDone)
        c.player_done = true;
      else
        c.records.push_back(std::move(rec));
      c.valid_bytes = r.at();
    } catch (const std::out_of_range& e) {
      c.tail_error = std::string("record at byte ") + std::to_string(start) + ": " + e.what() + " (" +
                     std::to_string(bytes.size() - start) + " bytes not read)";
      break;
    }
  }
  return c;
}

JournalContents readJournal(const std::string& path) {
  const std::optional<std::string> bytes = readWholeFileIfAny(path);
  if (!bytes) throw std::runtime_error("cannot read journal " + path);
  return parseJournal(*bytes, path);
}

MeasurementJournal::MeasurementJournal(const std::string& path, const JournalHeader& header, Opened* opened)
    : path_(path) {
  Opened o;
  std::uint64_t keep = 0;
  if (std::filesystem::exists(path)) {
    std::string other = "unreadable";
    try {
      JournalContents found = readJournal(path);
      other = found.header.run_id;
      if (found.header.run_id == header.run_id && found.header.name == header.name &&
          found.header.robots == header.robots) {
        keep = found.valid_bytes;
        o.resumed = true;
        if (!found.tail_error.empty()) o.note = "cut off a torn tail: " + found.tail_error;
        o.contents = std::move(found);
      }
    } catch (const std::runtime_error& e) { o.note = e.what(); }
    if (!o.resumed) {
      o.moved_to = path + "." + fileNameSafe(other) + ".old";
      std::filesystem::rename(path, o.moved_to);
      o.note = (o.note.empty() ? "" : o.note + "; ") + "a journal of run '" + other + "' (this run: '" + header.run_id +
               "') moved aside to " + o.moved_to;
    }
  }
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error(systemError("cannot open journal", path));
  if (o.resumed) {
    if (::ftruncate(fd_, static_cast<off_t>(keep)) != 0 || ::lseek(fd_, 0, SEEK_END) < 0)
      throw std::runtime_error(systemError("cannot cut the journal's torn tail", path));
  } else {
    if (::ftruncate(fd_, 0) != 0) throw std::runtime_error(systemError("cannot start journal", path));
    appendBytes(encodeJournalHeader(header));
  }
  appendBytes(markRecord(kSession));
  sync();
  if (!o.resumed) {  // the new file's directory entry too
    const std::string dir = std::filesystem::absolute(path).parent_path().string();
    const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
      ::fsync(dfd);
      ::close(dfd);
    }
  }
  if (opened) *opened = std::move(o);
}

MeasurementJournal::~MeasurementJournal() {
  if (fd_ >= 0) ::close(fd_);
}

void MeasurementJournal::appendBytes(const std::string& bytes) { buffer_ += bytes; }

void MeasurementJournal::append(const MeasurementRecord& record) {
  appendBytes(encodeJournalRecord(record));
  ++pending_records_;
}

void MeasurementJournal::appendDone() { appendBytes(markRecord(kDone)); }

void MeasurementJournal::sync() {
  std::size_t done = 0;
  while (done < buffer_.size()) {
    const ssize_t n = ::write(fd_, buffer_.data() + done, buffer_.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      buffer_.erase(0, done);  // what was written stays written; the rest is tried again
      throw std::runtime_error(systemError("cannot write journal", path_));
    }
    done += static_cast<std::size_t>(n);
  }
  buffer_.clear();
  if (::fdatasync(fd_) != 0) throw std::runtime_error(systemError("cannot sync journal", path_));
  pending_records_ = 0;
}

void MeasurementJournal::remove() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  std::filesystem::remove(path_);
}

}  // namespace cosmo::dataset
