#include "cosmo/dataset/recorder_session.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace cosmo::dataset {

namespace {

std::string journalFile(const std::string& output_dir, const std::string& name) {
  std::filesystem::create_directories(output_dir);
  return (std::filesystem::path(output_dir) / (name + ".journal")).string();
}

}  // namespace

std::string yamlQuoted(const std::string& text) {
  std::string q = "\"";
  for (const char c : text) q += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c == '\n' ? ' ' : c);
  return q + "\"";
}

RecorderSession::RecorderSession(const std::string& output_dir, JournalHeader run, NoiseModels noise, OutlierRule rule)
    : run_(std::move(run)),
      recorder_(run_.name, run_.robots, std::move(noise), rule),
      intake_(run_.robots),
      journal_(journalFile(output_dir, run_.name), run_, &opened_) {
  sessions_ = opened_.contents.sessions + 1;
  opening_.resumed = opened_.resumed;
  opening_.note = opened_.note;
  opening_.records = opened_.contents.records.size();
  if (opened_.resumed) {  // a recorder started on its own to write the journal of a run with a player
    run_.with_player = run_.with_player || opened_.contents.header.with_player;
    done_ = opened_.contents.player_done;
  }
  for (const MeasurementRecord& r : opened_.contents.records)
    if (intake_.take(r)) apply(r, nullptr);
  opened_ = {};  // replayed: the records are in the dataset now
}

bool RecorderSession::take(const MeasurementRecord& record, std::string* refused) {
  if (!intake_.take(record)) return false;
  journal_.append(record);
  apply(record, refused);
  return true;
}

void RecorderSession::apply(const MeasurementRecord& r, std::string* refused) {
  try {
    if (const KeyframeMeasurement* k = r.keyframe()) {
      std::optional<std::size_t> from;
      if (k->bridge_from) from = *k->bridge_from;
      recorder_.addKeyframe(k->robot, k->index, k->stamp, k->odometry, k->reference, from);
    } else {
      recorder_.addLoopClosure(*r.loopClosure());
    }
  } catch (const std::exception& e) {
    if (refused) *refused = e.what();
  }
}

void RecorderSession::durable() {
  if (journal_.unsynced()) journal_.sync();
}

void RecorderSession::playerDone() {
  if (done_) return;
  done_ = true;
  journal_.appendDone();
}

bool RecorderSession::stop(const std::string& why) {
  if (!incomplete_.empty()) return false;
  incomplete_ = why;
  return true;
}

void RecorderSession::end() {
  if (run_.with_player && !done_) stop("the run ended before the player finished the sequence (no /player/done)");
}

void RecorderSession::frontendSkipped(char robot, std::uint32_t scans) {
  frontend_skipped_[robot] = std::max(frontend_skipped_[robot], scans);
}

std::uint32_t RecorderSession::scansSkipped(char robot) const {
  const auto it = frontend_skipped_.find(robot);
  return std::max(intake_.scansSkipped(robot), it == frontend_skipped_.end() ? 0u : it->second);
}

MetadataLines RecorderSession::metadata(const MetadataLines& sequence_lines) const {
  MetadataLines lines = sequence_lines;
  lines.emplace_back("complete", incomplete_.empty() ? "true" : "false");
  if (!incomplete_.empty()) lines.emplace_back("incomplete", yamlQuoted(incomplete_));
  lines.emplace_back("run_id", yamlQuoted(run_.run_id));
  lines.emplace_back("recorder_sessions",
                     std::to_string(sessions_) + "  # recorder processes that wrote the journal (1: no restart)");
  std::string restarts = "{", skipped = "{";
  for (char r : run_.robots) {
    restarts += (restarts.size() > 1 ? ", " : "") + std::string(1, r) + ": " + std::to_string(intake_.restarts(r));
    skipped += (skipped.size() > 1 ? ", " : "") + std::string(1, r) + ": " + std::to_string(scansSkipped(r));
  }
  lines.emplace_back("frontend_restarts", restarts + "}  # restarts that took a keyframe (bridges: above)");
  lines.emplace_back("scans_skipped", skipped + "}  # skipped to keep up (real time: scan_queue)");
  return lines;
}

BuildReport RecorderSession::write(const std::string& path, const MetadataLines& sequence_lines, jrl::Dataset* built) {
  recorder_.setMetadata(metadata(sequence_lines));
  return recorder_.write(path, built);
}

std::string RecorderSession::writtenLine(const std::string& path, const std::string& why,
                                         const BuildReport& report) const {
  std::ostringstream out;
  out << "wrote " << path << " (" << why << (incomplete_.empty() ? "" : ", marked incomplete")
      << "): " << report.entries << " entries; " << recorder_.progressLine();
  if (!report.labelled) out << "; " << report.labels_note;
  if (report.keyframes_pending || report.loop_closures_pending)
    out << "; pending (not written yet): " << report.keyframes_pending << " keyframes, " << report.loop_closures_pending
        << " loop closures";
  return out.str();
}

bool RecorderSession::finish(bool written) {
  if (!written || !incomplete_.empty()) return false;
  journal_.remove();
  return true;
}

}  // namespace cosmo::dataset
