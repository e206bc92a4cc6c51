// comm_broker: the simulated radio between robots (cosmo::RadioSimulator, the paper's Algorithm 1) on ROS
// time.
//
// Subscribes  /<r>/keyframe_scans  (cosmo/Keyframe)  keyframe scans robot r offers to its teammates
//             /<r>/reference_pose  (geometry_msgs/PoseStamped, world frame)  r is "on" from its first pose;
//                                  after its last pose it stays on at that position
// Publishes   /<r>/received_scans  (cosmo/Keyframe, `sender` set) delivered scans; the cloud is the real
//                                  decompressed xz payload (x y z only)
//             /comm/links          (visualization_msgs/MarkerArray, frame `world`) active links, coloured by
//                                  their mean throughput so far (red 0 .. green B)
//             /comm/stats          (std_msgs/String, JSON, once per step batch) counters + active links
// Params      ~robots [a, b, c] (or "a,b,c"; absent: the player's sequence, /player/robots), ~comm wifi|proradio, ~config (a config/comm/*.yaml, wins over
//             ~comm), ~seed (int), ~size_model paper|real, ~timeout_mode no_progress|total_duration,
//             ~log_file (CSV of every transfer + <name>.summary.json; written every 30 s of ROS time and on
//             shutdown; empty = none), ~xz_preset (0..9, default 6), ~frame_id (default world),
//             ~compress_payload (default true; false with size_model paper skips xz, about 0.25 s of CPU per
//             64 x 1024 scan, and forwards the x y z points as they came, which xz's losslessness makes identical;
//             ignored, with a warning, under size_model real)
// Steps: every delta of ROS time (/clock under use_sim_time) on the grid k * delta, catching up when time jumps.
//   Each delivery carries its step time (Keyframe.received_at).
// Lockstep (~lockstep true, sequence.launch mode:=lockstep): no timer; the player drives the radio through
//   /comm/step_request (cosmo/RadioStepRequest: step through t once the listed keyframe offers arrived, with
//   these robots on) and the broker answers on /comm/step_done (cosmo/RadioStepDone: deliveries per receiver so
//   far) after publishing the deliveries. Grid, robot states and seed are the offline driver's
//   (pipeline::advanceRadio, the shared rule): radio time 0 at the sequence start rounded down to k * delta,
//   positions from the sequence's reference trajectories at the step time, seed deriveSeed(sequence seed, "radio")
//   (~seed is not used), all from the player's latched /player/sequence (cosmo/TeamSequence) and
//   /<r>/reference_trajectory (cosmo/ReferenceTrajectory): nothing is read from disk. Requests wait until they came.
//   Keyframe payloads: comm::PayloadStore, the one TeamRun holds.
#include <geometry_msgs/PoseStamped.h>
#include <ros/ros.h>
#include <std_msgs/String.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cosmo/ros/robot_list.hpp"
#include "cosmo/Keyframe.h"
#include "cosmo/RadioStepDone.h"
#include "cosmo/RadioStepRequest.h"
#include "cosmo/pipeline/seed_streams.hpp"
#include "cosmo/pipeline/team_radio.hpp"
#include "cosmo/ros/pose_msg.hpp"
#include "cosmo/ros/team_sequence_msg.hpp"
#include "cosmo/comm/payload_store.hpp"
#include "cosmo/comm/radio_simulator.hpp"
#include "cosmo/comm/scan_compression.hpp"
#include "cosmo/comm/transfer_log.hpp"
#include "cosmo/ros/point_cloud.hpp"

namespace {

std_msgs::ColorRGBA throughputColor(double fraction) {
  std_msgs::ColorRGBA c;
  const double f = std::clamp(fraction, 0.0, 1.0);
  c.r = static_cast<float>(f < 0.5 ? 1.0 : 2.0 * (1.0 - f));
  c.g = static_cast<float>(f < 0.5 ? 2.0 * f : 1.0);
  c.b = 0.0f;
  c.a = 1.0f;
  return c;
}

class CommBroker {
 public:
  CommBroker(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
    const std::vector<char> robots = cosmo::ros_glue::readTeamRobots(pnh);
    std::string comm = "wifi", config, size_model, timeout_mode;
    pnh.param<std::string>("comm", comm, comm);
    pnh.param<std::string>("config", config, "");
    cosmo::RadioParams params =
        config.empty() ? cosmo::RadioParams::byName(comm) : cosmo::RadioParams::fromConfig(cosmo::ConfigNode::load(config));
    if (pnh.getParam("size_model", size_model)) params.size_model = cosmo::sizeModelFromString(size_model, "~size_model");
    if (pnh.getParam("timeout_mode", timeout_mode))
      params.timeout_mode = cosmo::timeoutModeFromString(timeout_mode, "~timeout_mode");
    int seed = 0;
    pnh.param("seed", seed, 0);
    pnh.param("xz_preset", xz_preset_, 6);
    if (xz_preset_ < 0 || xz_preset_ > 9) throw std::runtime_error("~xz_preset: must be in 0..9");
    pnh.param<std::string>("log_file", log_file_, "");
    pnh.param<std::string>("frame_id", frame_id_, "world");
    pnh.param("compress_payload", compress_, true);
    if (!compress_ && params.size_model == cosmo::RadioParams::SizeModel::RealCompressed) {
      ROS_WARN("comm_broker: ~compress_payload false ignored: the real size model needs the xz payload");
      compress_ = true;
    }
    pnh.param("lockstep", lockstep_, false);
    sim_ = std::make_unique<cosmo::RadioSimulator>(params, robots, static_cast<std::uint64_t>(seed));
    payloads_ = std::make_unique<cosmo::PayloadStore>(compress_, static_cast<std::uint32_t>(xz_preset_));

    for (char r : sim_->robots()) {
      const std::string ns(1, r);
      keyframe_subs_.push_back(nh.subscribe<cosmo::Keyframe>(
          ns + "/keyframe_scans", 100, [this, r](const cosmo::Keyframe::ConstPtr& m) { onKeyframe(r, *m); }));
      pose_subs_.push_back(nh.subscribe<geometry_msgs::PoseStamped>(
          ns + "/reference_pose", 20, [this, r](const geometry_msgs::PoseStamped::ConstPtr& m) { onPose(r, *m); }));
      received_pubs_[r] = nh.advertise<cosmo::Keyframe>(ns + "/received_scans", 100);
    }
    links_pub_ = nh.advertise<visualization_msgs::MarkerArray>("comm/links", 2);
    stats_pub_ = nh.advertise<std_msgs::String>("comm/stats", 10);
    if (lockstep_) {
      sequence_sub_ = nh.subscribe<cosmo::TeamSequence>(
          cosmo::ros_glue::kTeamSequenceTopic, 1, [this](const cosmo::TeamSequence::ConstPtr& m) { onSequence(*m); });
      for (char r : sim_->robots())
        trajectory_subs_.push_back(nh.subscribe<cosmo::ReferenceTrajectory>(
            cosmo::ros_glue::referenceTrajectoryTopic(r), 1,
            [this, r](const cosmo::ReferenceTrajectory::ConstPtr& m) { onTrajectory(r, *m); }));
      step_done_pub_ = nh.advertise<cosmo::RadioStepDone>("comm/step_done", 100);
      step_request_sub_ = nh.subscribe<cosmo::RadioStepRequest>(
          "comm/step_request", 100, [this](const cosmo::RadioStepRequest::ConstPtr& m) { onStepRequest(*m); });
    } else {
      timer_ = nh.createWallTimer(ros::WallDuration(0.01), [this](const ros::WallTimerEvent&) { onTimer(); });
    }
    ROS_INFO("comm_broker: %zu robots, B %.0f kB/s, d_init %.0f m, d_intf %.0f m, P_max %.2f, seed %s, sizes %s, timeout %s%s",
             robots.size(), params.bandwidth_kBps, params.d_init, params.d_intf, params.p_max,
             lockstep_ ? "from the sequence" : std::to_string(seed).c_str(),
             cosmo::toString(params.size_model).c_str(), cosmo::toString(params.timeout_mode).c_str(),
             lockstep_ ? ", lockstep (driven by the player)" : "");
  }

  ~CommBroker() { writeLog(); }

  void writeLog() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (log_file_.empty()) return;
    try {
      cosmo::writeTransferLog(log_file_, sim_->transferLog(), sim_->stats(), sim_->params());
    } catch (const std::exception& e) {
      ROS_ERROR("comm_broker: %s", e.what());
    }
  }

 private:
  /// What a delivery carries besides the scan (which the payload store holds).
  struct Stored {
    std_msgs::Header header;
    geometry_msgs::Pose reference;
    bool has_reference = false;
  };

  void onKeyframe(char r, const cosmo::Keyframe& m) {
    const std::string topic = std::string("/") + r + "/keyframe_scans";
    if (!m.robot.empty() && m.robot != std::string(1, r))
      ROS_WARN_THROTTLE(5.0, "comm_broker: %s: message says robot '%s'; using '%c'", topic.c_str(), m.robot.c_str(), r);
    Stored s;
    cosmo::PayloadStore::Payload payload;
    try {
      auto scan = std::make_shared<cosmo::Scan>();  // only x y z travel
      scan->points = cosmo::ros_glue::fromPointCloud2(m.cloud, true, topic).points;
      payload = payloads_->pack(std::move(scan));  // xz outside the lock
    } catch (const std::exception& e) {
      ROS_ERROR("comm_broker: dropping keyframe %u: %s", m.index, e.what());
      std::lock_guard<std::mutex> lock(mutex_);
      ++offers_received_[r];  // counted, so that a lockstep step waiting for it goes on
      runPendingSteps();
      return;
    }
    s.header = m.header;
    s.header.frame_id = m.header.frame_id.empty() ? m.cloud.header.frame_id : m.header.frame_id;
    s.reference = m.reference;
    s.has_reference = m.has_reference;
    std::lock_guard<std::mutex> lock(mutex_);
    const cosmo::PayloadStore::Sizes sizes = payloads_->store(r, m.index, std::move(payload));
    sim_->offerKeyframe(r, m.index, sizes.payload, sizes.raw);
    if (lockstep_ && !lockstep_ready_) early_offers_.push_back({r, m.index, sizes});  // offered again once seeded
    store_[{r, m.index}] = std::move(s);
    ++offers_received_[r];
    runPendingSteps();
  }

  void onPose(char r, const geometry_msgs::PoseStamped& m) {
    if (lockstep_) {  // positions from the sequence's references; kept for robots without one
      std::lock_guard<std::mutex> lock(mutex_);
      last_position_[r] = Eigen::Vector3d(m.pose.position.x, m.pose.position.y, m.pose.position.z);
      return;
    }
    const auto& p = m.pose.position;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      ROS_WARN_THROTTLE(5.0, "comm_broker: /%c/reference_pose: non-finite position ignored", r);
      return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    sim_->setRobotState(r, Eigen::Vector3d(p.x, p.y, p.z), true);
  }

  void onTimer() {
    const ros::Time now_ros = ros::Time::now();
    if (now_ros.isZero()) return;  // sim time before the first /clock
    const double now = now_ros.toSec();
    std::vector<std::pair<double, cosmo::Transfer>> ended;  // (step time, transfer)
    double t_last = 0.0;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      const double dt = sim_->params().step;
      if (!started_ || now - sim_->nextStepTime() > 3600.0) {
        if (started_) ROS_WARN("comm_broker: ROS time jumped forward by more than an hour; restarting the step grid");
        sim_->setStartTime(std::ceil(now / dt - 1e-9) * dt);
        started_ = true;
      } else if (sim_->nextStepTime() - now > 1.0) {
        ROS_WARN_THROTTLE(5.0, "comm_broker: ROS time went backwards (%.3f s < %.3f s); waiting", now,
                          sim_->nextStepTime());
      }
      int steps = 0;
      std::map<std::pair<char, char>, cosmo::ActiveCommunication> links;  // links of this batch of steps
      while (sim_->nextStepTime() <= now + 1e-9) {
        t_last = sim_->nextStepTime();
        for (const cosmo::Transfer& x : sim_->step(t_last)) ended.emplace_back(t_last, x);
        for (const auto& c : sim_->lastStepCommunications()) links[{c.sender, c.receiver}] = c;
        ++steps;
      }
      if (steps == 0) return;
      for (const auto& [t, x] : ended) deliver(x, ros::Time(t));
      publishLinks(now_ros, t_last, links);
      publishStats(t_last);
      writeLogEvery30s(t_last);
    }
  }

  // Lockstep: the player's resolved sequence (latched): grid origin and radio seed, then every robot's reference.
  void onSequence(const cosmo::TeamSequence& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    sequence_ = m;
    for (char r : sim_->robots())
      if (m.robots.find(r) == std::string::npos) {
        ROS_ERROR("comm_broker: robot %c is not in the player's sequence (%s): positions from its reference_pose", r,
                  m.robots.c_str());
        references_[r] = cosmo::Trajectory{};
      }
    startLockstep();
  }

  void onTrajectory(char r, const cosmo::ReferenceTrajectory& m) {
    cosmo::Trajectory reference;
    try {
      reference = cosmo::ros_glue::trajectoryFromMsg(m, cosmo::ros_glue::referenceTrajectoryTopic(r));
    } catch (const std::exception& e) {
      ROS_ERROR("comm_broker: %s; positions from its reference_pose", e.what());
    }
    std::lock_guard<std::mutex> lock(mutex_);
    references_[r] = std::move(reference);
    startLockstep();
  }

  // Lockstep, with the mutex held, once the sequence and every reference arrived: grid origin and radio seed as
  // the offline driver's, the front-ends connected; then the requests waiting for it run.
  void startLockstep() {
    if (lockstep_ready_ || !sequence_) return;
    for (char r : sim_->robots())
      if (!references_.count(r)) return;
    waitForFrontends();
    origin_ = cosmo::pipeline::radioGridOrigin(sequence_->start.toNSec(), sim_->params().step);
    const std::uint64_t seed = cosmo::pipeline::deriveSeed(sequence_->seed, "radio");
    sim_ = std::make_unique<cosmo::RadioSimulator>(sim_->params(), sim_->robots(), seed);
    for (const auto& o : early_offers_) sim_->offerKeyframe(o.robot, o.index, o.sizes.payload, o.sizes.raw);
    early_offers_.clear();
    lockstep_ready_ = true;
    ROS_INFO("comm_broker: lockstep on sequence %s (seed %llu): radio seed %llu, grid origin %.3f s",
             sequence_->name.c_str(), static_cast<unsigned long long>(sequence_->seed),
             static_cast<unsigned long long>(seed), cosmo::toSeconds(origin_));
    runPendingSteps();
  }

  // Every front-end's offers and deliveries connected (a message sent before its connection exists is lost).
  void waitForFrontends() {
    const ros::WallTime wait_start = ros::WallTime::now();
    auto connected = [&] {
      for (const auto& sub : keyframe_subs_)
        if (sub.getNumPublishers() == 0) return false;
      for (const auto& [r, pub] : received_pubs_)
        if (pub.getNumSubscribers() == 0) return false;
      return true;
    };
    while (ros::ok() && !connected() && (ros::WallTime::now() - wait_start).toSec() < 30.0) ros::WallDuration(0.05).sleep();
    if (!connected()) ROS_WARN("comm_broker: lockstep: not every front-end is connected; going on");
  }

  void onStepRequest(const cosmo::RadioStepRequest& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_steps_.push_back(m);
    runPendingSteps();
  }

  // Lockstep, with the mutex held: runs the pending requests, in order, whose keyframe offers all arrived.
  void runPendingSteps() {
    if (lockstep_ && !lockstep_ready_) return;  // the sequence has not arrived yet
    while (!pending_steps_.empty()) {
      const cosmo::RadioStepRequest& m = pending_steps_.front();
      std::map<char, bool> on;
      for (std::size_t i = 0; i < m.robots.size(); ++i) {
        const char r = m.robots[i];
        if (i < m.keyframes.size() && offers_received_[r] < m.keyframes[i]) return;  // an offer is on its way
        on[r] = i < m.on.size() && m.on[i];
      }
      cosmo::StampNs last_step = 0;
      const auto state = [&](char r, cosmo::StampNs step_stamp) {
        last_step = step_stamp;
        cosmo::pipeline::RadioRobotState s;
        s.on = on.count(r) && on[r];
        const auto last = last_position_.find(r);
        s.position = cosmo::pipeline::radioPosition(references_[r], step_stamp,
                                                    last == last_position_.end() ? Eigen::Vector3d::Zero() : last->second);
        return s;
      };
      const auto on_transfer = [&](cosmo::StampNs step_stamp, const cosmo::Transfer& x) {
        deliver(x, cosmo::ros_glue::stampToRos(step_stamp));
      };
      if (cosmo::pipeline::advanceRadio(*sim_, origin_, m.stamp.toNSec(), state, on_transfer) > 0) {
        std::map<std::pair<char, char>, cosmo::ActiveCommunication> links;  // of the last step
        for (const auto& c : sim_->lastStepCommunications()) links[{c.sender, c.receiver}] = c;
        const double radio_time = cosmo::toSeconds(last_step - origin_);
        publishLinks(cosmo::ros_glue::stampToRos(last_step), radio_time, links);
        publishStats(cosmo::toSeconds(last_step));
        last_step_ = last_step;
        writeLogEvery30s(radio_time);
      }
      cosmo::RadioStepDone done;
      done.seq = m.seq;
      done.stamp = cosmo::ros_glue::stampToRos(last_step_);
      done.next_stamp = cosmo::ros_glue::stampToRos(cosmo::pipeline::nextRadioStepStamp(*sim_, origin_));
      for (char r : sim_->robots()) {
        done.robots.push_back(r);
        done.delivered.push_back(delivered_[r]);
      }
      step_done_pub_.publish(done);
      pending_steps_.pop_front();
    }
  }

  // Called with the mutex held. `when`: the step the transfer ended in.
  void deliver(const cosmo::Transfer& x, const ros::Time& when) {
    if (x.outcome != cosmo::Transfer::Outcome::Delivered) {
      ROS_DEBUG("comm_broker: %c -> %c keyframe %zu timed out", x.sender, x.receiver, x.keyframe);
      return;
    }
    auto it = store_.find({x.sender, x.keyframe});
    if (it == store_.end()) return;
    const Stored& s = it->second;
    cosmo::Keyframe out;
    try {
      const std::shared_ptr<const cosmo::Scan> scan = payloads_->deliver(x.sender, x.keyframe);
      out.cloud = cosmo::ros_glue::toPointCloud2(*scan, s.header.frame_id);
    } catch (const std::exception& e) {
      ROS_ERROR("comm_broker: keyframe %c%zu: %s", x.sender, x.keyframe, e.what());
      return;
    }
    out.header = s.header;
    out.cloud.header = s.header;
    out.robot = std::string(1, x.sender);
    out.index = static_cast<std::uint32_t>(x.keyframe);
    out.reference = s.reference;
    out.has_reference = s.has_reference;
    out.sender = std::string(1, x.sender);
    out.received_at = when;
    received_pubs_.at(x.receiver).publish(out);
    ++delivered_[x.receiver];
    ROS_DEBUG("comm_broker: delivered %c%zu to %c (%zu bytes, %.1f s)", x.sender, x.keyframe, x.receiver, x.bytes,
              x.end - x.start);
  }

  void publishLinks(const ros::Time& stamp, double t,
                    const std::map<std::pair<char, char>, cosmo::ActiveCommunication>& links) {
    visualization_msgs::Marker m;
    m.header.frame_id = frame_id_;
    m.header.stamp = stamp;
    m.ns = "comm_links";
    m.id = 0;
    m.pose.orientation.w = 1.0;
    if (links.empty()) {
      m.action = visualization_msgs::Marker::DELETE;
    } else {
      m.type = visualization_msgs::Marker::LINE_LIST;
      m.action = visualization_msgs::Marker::ADD;
      m.scale.x = 0.5;
      const double step = sim_->params().step;
      for (const auto& [pair, c] : links) {
        const double duration = t - c.start + step;  // steps so far * delta
        const double mean_rate = c.bytes_delivered / std::max(duration, step);
        const std_msgs::ColorRGBA color = throughputColor(mean_rate / sim_->params().bandwidthBps());
        for (char r : {c.sender, c.receiver}) {
          const Eigen::Vector3d p = sim_->position(r);
          geometry_msgs::Point q;
          q.x = p.x();
          q.y = p.y();
          q.z = p.z();
          m.points.push_back(q);
          m.colors.push_back(color);
        }
      }
      m.color = m.colors.front();
    }
    visualization_msgs::MarkerArray array;
    array.markers.push_back(m);
    links_pub_.publish(array);
  }

  /// The transfer log (CSV + summary) rewritten when 30 s of radio time passed since the last write.
  void writeLogEvery30s(double radio_time) {
    if (log_file_.empty() || radio_time - last_log_write_ < 30.0) return;
    last_log_write_ = radio_time;
    try {
      cosmo::writeTransferLog(log_file_, sim_->transferLog(), sim_->stats(), sim_->params());
    } catch (const std::exception& ex) {
      ROS_ERROR_THROTTLE(30.0, "comm_broker: %s", ex.what());
    }
  }

  void publishStats(double t) {
    nlohmann::json j = cosmo::transferSummary(sim_->stats(), sim_->params());
    j["time"] = t;
    j["active"] = nlohmann::json::array();
    for (const auto& c : sim_->activeCommunications())
      j["active"].push_back({{"sender", std::string(1, c.sender)},
                             {"receiver", std::string(1, c.receiver)},
                             {"keyframe", c.keyframe},
                             {"bytes", c.bytes},
                             {"progress", c.bytes ? c.bytes_delivered / static_cast<double>(c.bytes) : 1.0},
                             {"distance", c.distance},
                             {"interference", c.interference}});
    nlohmann::json pending = nlohmann::json::object();
    for (char a : sim_->robots())
      for (char b : sim_->robots())
        if (a != b) pending[std::string(1, a) + "->" + std::string(1, b)] = sim_->undeliveredCount(a, b);
    j["pending"] = pending;
    std_msgs::String msg;
    msg.data = j.dump();
    stats_pub_.publish(msg);
  }

  std::mutex mutex_;
  std::unique_ptr<cosmo::RadioSimulator> sim_;
  std::unique_ptr<cosmo::PayloadStore> payloads_;
  std::map<std::pair<char, std::size_t>, Stored> store_;
  std::vector<ros::Subscriber> keyframe_subs_, pose_subs_;
  std::map<char, ros::Publisher> received_pubs_;
  ros::Publisher links_pub_, stats_pub_;
  ros::WallTimer timer_;
  // lockstep
  bool lockstep_ = false, lockstep_ready_ = false;
  cosmo::StampNs origin_ = 0, last_step_ = 0;
  std::map<char, cosmo::Trajectory> references_;  ///< from the player, one per robot (empty: none)
  std::optional<cosmo::TeamSequence> sequence_;
  struct Offer {
    char robot;
    std::uint32_t index;
    cosmo::PayloadStore::Sizes sizes;
  };
  std::vector<Offer> early_offers_;  ///< offers before the sequence arrived (the radio is re-seeded then)
  ros::Subscriber sequence_sub_;
  std::vector<ros::Subscriber> trajectory_subs_;
  std::map<char, Eigen::Vector3d> last_position_;
  std::map<char, std::uint32_t> offers_received_, delivered_;
  std::deque<cosmo::RadioStepRequest> pending_steps_;
  ros::Subscriber step_request_sub_;
  ros::Publisher step_done_pub_;
  int xz_preset_ = 6;
  bool compress_ = true;
  std::string log_file_, frame_id_;
  bool started_ = false;
  double last_log_write_ = 0.0;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "comm_broker");
  ros::NodeHandle nh, pnh("~");
  std::unique_ptr<CommBroker> broker;
  try {
    broker = std::make_unique<CommBroker>(nh, pnh);
  } catch (const std::exception& e) {
    ROS_FATAL("comm_broker: %s", e.what());
    return 1;
  }
  ros::AsyncSpinner spinner(2);  // compression of offered scans does not hold up the steps
  spinner.start();
  ros::waitForShutdown();
  spinner.stop();
  broker->writeLog();
  return 0;
}
