#pragma once
// The recorder's journal, <output_dir>/<name>.journal: every measurement the recorder took, appended and synced to
// disk (fdatasync) before it is acknowledged, so that a recorder killed at any moment loses nothing it
// acknowledged, and a respawned one resumes from it.
//
// Format (little-endian; docs/design.md):
//   header   "COSMOJNL" | u32 version (1) | u32 n | n bytes: str run_id, str name, str robots, u8 with_player |
//            u32 CRC-32 of them
//   record   u32 n | u32 CRC-32 of the n payload bytes | payload: u8 kind, then
//            kind 1 keyframe:     u8 robot, u64 seq, u32 index, u64 stamp, pose odometry, u8 has_reference,
//                                 [pose reference], u8 bridged, u32 bridge_from, u32 scans_skipped
//            kind 2 loop closure: u8 robot, u64 seq, u8 owner, u64 key1, u64 key2, u64 computed_at, pose measurement
//            kind 3 session:      a recorder process opened the journal
//            kind 4 done:         the player finished the sequence (the dataset is complete)
//   str = u32 length + bytes; pose = 12 f64 (rotation row-major, then translation): bit-exact.
// A reader keeps the valid prefix: the first record that is cut short or fails its CRC ends it (a torn tail after
// a SIGKILL), reported with its byte offset.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "cosmo/dataset/measurement_record.hpp"

namespace cosmo::dataset {

struct JournalHeader {
  std::string run_id;  ///< the run the measurements belong to
  std::string name;    ///< the dataset
  std::vector<char> robots;
  bool with_player = false;  ///< a player runs the sequence: the dataset is complete once it finished
};

/// What a journal holds.
struct JournalContents {
  JournalHeader header;
  std::vector<MeasurementRecord> records;
  std::size_t sessions = 0;      ///< recorder processes that opened it
  bool player_done = false;      ///< a "done" record: the player finished the sequence
  std::uint64_t valid_bytes = 0;  ///< the valid prefix: header and whole records
  std::uint64_t file_bytes = 0;
  std::string tail_error;  ///< why the bytes after valid_bytes were not read (empty: none left)
};

/// Parses a journal's bytes (`source` names it in messages). Throws std::runtime_error when the header is not a
/// journal's (magic, version, CRC, size); a bad record ends the valid prefix instead (tail_error).
JournalContents parseJournal(std::string_view bytes, const std::string& source);
/// Reads the file at `path` (throws std::runtime_error naming it when it cannot be read or has no valid header).
JournalContents readJournal(const std::string& path);

/// The record's and the header's encodings (tests, fuzzing).
std::string encodeJournalHeader(const JournalHeader& header);
std::string encodeJournalRecord(const MeasurementRecord& record);

class MeasurementJournal {
 public:
  /// What open() did, for the log.
  struct Opened {
    JournalContents contents;  ///< what was replayed (no records when a new journal was made)
    bool resumed = false;      ///< this run's journal was found and continued
    std::string moved_to;      ///< another run's journal was moved aside to this path
    std::string note;          ///< a torn tail cut off, a journal moved aside
  };

  /// Opens `path` for the run of `header`: a journal of the same run id, name and robots is read (its valid prefix: a torn tail is
  /// cut off) and continued; one of another run, or one whose header cannot be read, is moved aside to
  /// "<path>.<its run id, or 'unreadable'>.old", never merged; otherwise a new one is made. Then a session record
  /// is appended and synced. Throws std::runtime_error naming the path on I/O errors.
  MeasurementJournal(const std::string& path, const JournalHeader& header, Opened* opened = nullptr);
  ~MeasurementJournal();
  MeasurementJournal(const MeasurementJournal&) = delete;
  MeasurementJournal& operator=(const MeasurementJournal&) = delete;

  /// Queues a record; it is on disk after the next sync().
  void append(const MeasurementRecord& record);
  /// Queues the record that the player finished the sequence.
  void appendDone();
  /// Writes what was appended and waits until it is on disk (fdatasync). Throws std::runtime_error on I/O errors.
  void sync();
  /// Records appended and not synced yet.
  std::size_t pending() const { return pending_records_; }
  /// Something was appended and not synced yet (records or marks).
  bool unsynced() const { return !buffer_.empty(); }
  const std::string& path() const { return path_; }
  /// Removes the journal file (the dataset was written complete).
  void remove();

 private:
  void appendBytes(const std::string& bytes);
  std::string path_;
  int fd_ = -1;
  std::string buffer_;
  std::size_t pending_records_ = 0;
};

}  // namespace cosmo::dataset
