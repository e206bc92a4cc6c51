#include "cosmo/ros/recorder_msgs.hpp"

#include <stdexcept>

#include "cosmo/jrl/dataset.hpp"
#include "cosmo/ros/pose_msg.hpp"

namespace cosmo::ros_glue {

namespace {
char oneChar(const std::string& field, const char* name) {
  if (field.size() != 1) throw std::invalid_argument(std::string(name) + " '" + field + "' is not one character");
  return field[0];
}

/// The index of `robot` in the message's robot list, when listed with every per-robot array.
std::optional<std::size_t> slot(const cosmo::RecorderProgress& m, char robot) {
  const std::size_t i = m.robots.find(robot);
  if (i == std::string::npos) return std::nullopt;
  const std::size_t n = m.robots.size();
  if (m.acked.size() != n || m.highest.size() != n || m.next_index.size() != n || m.chain_end.size() != n ||
      m.scans_skipped.size() != n)
    return std::nullopt;
  return i;
}
}  // namespace

dataset::MeasurementRecord measurementFromMsg(const cosmo::RecorderKeyframe& m, char topic_robot) {
  if (oneChar(m.robot, "robot") != topic_robot)
    throw std::invalid_argument("robot field '" + m.robot + "' differs from the topic's robot");
  dataset::KeyframeMeasurement k;
  k.robot = topic_robot;
  k.index = m.index;
  k.stamp = m.header.stamp.toNSec();
  k.odometry = m.index == 0 || m.bridge ? Pose3::Identity()
                                        : poseFromExactOrMsg(m.odometry_from_previous_exact, m.odometry_from_previous);
  if (m.has_reference) k.reference = poseFromExactOrMsg(m.reference_exact, m.reference);
  if (m.bridge) k.bridge_from = m.bridge_from;
  k.scans_skipped = m.scans_skipped;
  return dataset::MeasurementRecord{topic_robot, m.seq, k};
}

dataset::MeasurementRecord measurementFromMsg(const cosmo::RecorderLoopClosure& m, char topic_robot) {
  dataset::LoopClosureMeasurement lc;
  lc.owner = oneChar(m.owner, "owner");
  if (lc.owner != topic_robot)
    throw std::invalid_argument("owner field '" + m.owner + "' differs from the topic's robot");
  lc.computed_at = m.header.stamp.toNSec();
  lc.key1 = jrl::symbol(oneChar(m.robot1, "robot1"), m.index1);
  lc.key2 = jrl::symbol(oneChar(m.robot2, "robot2"), m.index2);
  lc.measurement = poseFromExactOrMsg(m.measurement_exact, m.measurement);
  return dataset::MeasurementRecord{topic_robot, m.seq, lc};
}

cosmo::RecorderProgress recorderProgressMsg(const dataset::RecorderIntake& intake,
                                            const dataset::DatasetRecorder& recorder) {
  cosmo::RecorderProgress p;
  for (char r : intake.robots()) {
    p.robots.push_back(r);
    p.keyframes.push_back(static_cast<std::uint32_t>(intake.keyframes(r)));
    p.loop_closures.push_back(static_cast<std::uint32_t>(intake.loopClosures(r)));
    p.acked.push_back(intake.acked(r));
    p.highest.push_back(intake.highest(r));
    p.next_index.push_back(intake.nextIndex(r));
    const std::optional<std::size_t> end = recorder.chainEnd(r);
    p.chain_end.push_back(end ? static_cast<std::int32_t>(*end) : -1);
    p.scans_skipped.push_back(intake.scansSkipped(r));
  }
  return p;
}

live::RecorderHolding recorderHolding(const cosmo::RecorderProgress& m, char robot) {
  live::RecorderHolding h;
  const std::optional<std::size_t> i = slot(m, robot);
  if (!i) return h;
  h.highest_seq = m.highest[*i];
  h.next_index = m.next_index[*i];
  if (m.chain_end[*i] >= 0) h.chain_end = static_cast<std::uint32_t>(m.chain_end[*i]);
  h.scans_skipped = m.scans_skipped[*i];
  return h;
}

std::uint64_t recorderAcked(const cosmo::RecorderProgress& m, char robot) {
  const std::optional<std::size_t> i = slot(m, robot);
  return i ? m.acked[*i] : 0;
}

cosmo::RecorderProgress recorderProgressMsg(const dataset::RecorderSession& s, const std::string& session,
                                            const std::string& written) {
  cosmo::RecorderProgress p = recorderProgressMsg(s.intake(), s.recorder());
  for (std::size_t i = 0; i < p.robots.size(); ++i)
    p.scans_skipped[i] = std::max(p.scans_skipped[i], s.scansSkipped(p.robots[i]));
  p.run_id = s.run().run_id;
  p.session = session;
  p.incomplete = s.incomplete();
  p.written = written;
  return p;
}

}  // namespace cosmo::ros_glue
