#pragma once
// One recorder process's session of a run: the recorder node's whole policy, without ROS.
//   take      a sender's numbered measurement: a duplicate is dropped (RecorderIntake); a new one is appended to
//             the journal <output_dir>/<name>.journal (MeasurementJournal) and goes into the dataset
//             (DatasetRecorder; one it refuses stays journalled and acknowledged, the refusal reported);
//   durable   the journal synced to disk: only then may what was taken be acknowledged (the node publishes its
//             progress after durable()), so a recorder killed at any moment loses nothing it acknowledged;
//   resume    a session that opens its run's journal replays it (a torn tail cut off, another run's journal moved
//             aside) and goes on; the number of sessions is in the metadata;
//   the end   complete when the player finished the sequence (or no player runs it) and nothing stopped the run;
//             else the dataset so far, marked incomplete with the first reason; a complete dataset, once written,
//             removes the journal.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cosmo/dataset/dataset_recorder.hpp"
#include "cosmo/dataset/measurement_journal.hpp"
#include "cosmo/dataset/recorder_intake.hpp"

namespace cosmo::dataset {

using MetadataLines = std::vector<std::pair<std::string, std::string>>;

class RecorderSession {
 public:
  /// What opening the journal did, for the log.
  struct Opening {
    bool resumed = false;
    std::size_t records = 0;  ///< measurements replayed
    std::string note;         ///< a torn tail cut off, another run's journal moved aside
  };

  /// `run`: the run id, the dataset name, the robots and whether a player runs the sequence. Opens (or continues)
  /// <output_dir>/<name>.journal. Throws std::runtime_error naming the path on I/O errors.
  RecorderSession(const std::string& output_dir, JournalHeader run, NoiseModels noise, OutlierRule rule);

  const Opening& opening() const { return opening_; }
  const JournalHeader& run() const { return run_; }
  const std::string& journalPath() const { return journal_.path(); }
  /// Recorder processes that opened the journal, this one included.
  std::size_t sessions() const { return sessions_; }

  /// A measurement from its sender; false for a duplicate. `refused`: why the dataset did not take a new one.
  bool take(const MeasurementRecord& record, std::string* refused = nullptr);
  /// The journal on disk: everything taken so far may be acknowledged.
  void durable();
  /// The player finished the sequence (journalled: a resumed session knows).
  void playerDone();
  bool playerFinished() const { return done_; }
  /// The run stops short: the dataset is incomplete (the first reason is kept; true when this was the first).
  bool stop(const std::string& why);
  /// At the end of the process: a run with a player that did not finish is incomplete.
  void end();
  const std::string& incomplete() const { return incomplete_; }
  /// The front-end's own count of skipped scans (its acks: also after its last keyframe).
  void frontendSkipped(char robot, std::uint32_t scans);
  std::uint32_t scansSkipped(char robot) const;

  /// The dataset's metadata: `sequence_lines` (the sequence's, trials::sequenceMetadata), then whether it is
  /// complete (and why not), the run id, the sessions, the front-ends' restarts and skipped scans.
  MetadataLines metadata(const MetadataLines& sequence_lines) const;
  /// Writes the dataset with that metadata to `path` (atomically). Throws std::runtime_error when it cannot.
  BuildReport write(const std::string& path, const MetadataLines& sequence_lines, jrl::Dataset* built = nullptr);
  /// The line a write is logged with: "wrote <path> (<why>[, marked incomplete]): <n> entries; <progress>", then
  /// why it is not labelled and what is pending, when so.
  std::string writtenLine(const std::string& path, const std::string& why, const BuildReport& report) const;
  /// After the last write: a complete dataset that was written removes the journal (true when it did).
  bool finish(bool written);

  const RecorderIntake& intake() const { return intake_; }
  const DatasetRecorder& recorder() const { return recorder_; }

 private:
  void apply(const MeasurementRecord& record, std::string* refused);

  JournalHeader run_;
  DatasetRecorder recorder_;
  RecorderIntake intake_;
  MeasurementJournal::Opened opened_;  ///< filled by the journal's constructor, replayed, then cleared
  MeasurementJournal journal_;
  Opening opening_;
  std::size_t sessions_ = 1;
  bool done_ = false;
  std::string incomplete_;
  std::map<char, std::uint32_t> frontend_skipped_;
};

/// A YAML double-quoted scalar of `text` (newlines as spaces).
std::string yamlQuoted(const std::string& text);

}  // namespace cosmo::dataset
