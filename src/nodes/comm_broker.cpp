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
// Params      ~robots [a, b, c] (or "a,b,c"; absent: the player's sequence, /player/robots), ~comm wifi|proradio,
// ~config (a config/comm/*.yaml, wins over
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
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include "cosmo/Keyframe.h"
#include "cosmo/RadioStepDone.h"
#include "cosmo/RadioStepRequest.h"
#include "cosmo/comm/payload_store.hpp"
#include "cosmo/comm/radio_simulator.hpp"
#include "cosmo/comm/radio_status.hpp"
#include "cosmo/comm/transfer_log.hpp"
#include "cosmo/pipeline/radio_step_queue.hpp"
#include "cosmo/pipeline/seed_streams.hpp"
#include "cosmo/pipeline/team_radio.hpp"
#include "cosmo/ros/markers.hpp"
#include "cosmo/ros/node_main.hpp"
#include "cosmo/ros/point_cloud.hpp"
#include "cosmo/ros/pose_msg.hpp"
#include "cosmo/ros/robot_list.hpp"
#include "cosmo/ros/team_sequence_msg.hpp"

using namespace cosmo;

namespace {

using Links = std::map<std::pair<char, char>, ActiveCommunication>;

struct Options {
  std::vector<char> robots;
  RadioParams radio;
  int seed = 0, xz_preset = 6;
  std::string log_file, frame_id = "world";
  bool compress = true, lockstep = false;
};

RadioParams readRadioParams(const ros::NodeHandle& pnh) {
  std::string comm = "wifi", config, size_model, timeout_mode;
  pnh.param<std::string>("comm", comm, comm);
  pnh.param<std::string>("config", config, "");
  RadioParams params = config.empty() ? RadioParams::byName(comm) : RadioParams::fromConfig(ConfigNode::load(config));
  if (pnh.getParam("size_model", size_model)) params.size_model = sizeModelFromString(size_model, "~size_model");
  if (pnh.getParam("timeout_mode", timeout_mode))
    params.timeout_mode = timeoutModeFromString(timeout_mode, "~timeout_mode");
  return params;
}

Options readOptions(const ros::NodeHandle& pnh) {
  Options o;
  o.robots = ros_glue::readTeamRobots(pnh);
  o.radio = readRadioParams(pnh);
  pnh.param("seed", o.seed, 0);
  pnh.param("xz_preset", o.xz_preset, 6);
  if (o.xz_preset < 0 || o.xz_preset > 9) throw std::runtime_error("~xz_preset: must be in 0..9");
  pnh.param<std::string>("log_file", o.log_file, "");
  pnh.param<std::string>("frame_id", o.frame_id, "world");
  pnh.param("compress_payload", o.compress, true);
  if (!o.compress && o.radio.size_model == RadioParams::SizeModel::RealCompressed) {
    ROS_WARN("comm_broker: ~compress_payload false ignored: the real size model needs the xz payload");
    o.compress = true;
  }
  pnh.param("lockstep", o.lockstep, false);
  return o;
}

pipeline::QueuedRadioStep stepFromMsg(const cosmo::RadioStepRequest& m) {
  pipeline::QueuedRadioStep q;
  q.seq = m.seq;
  q.order.through = m.stamp.toNSec();
  q.order.robots.assign(m.robots.begin(), m.robots.end());
  q.order.on.assign(m.on.begin(), m.on.end());
  q.order.keyframes = m.keyframes;
  return q;
}

class CommBroker {
 public:
  CommBroker(ros::NodeHandle& nh, Options options)
      : o_(std::move(options)),
        sim_(std::make_unique<RadioSimulator>(o_.radio, o_.robots, static_cast<std::uint64_t>(o_.seed))),
        payloads_(o_.compress, static_cast<std::uint32_t>(o_.xz_preset)) {
    connectRobots(nh);
    if (o_.lockstep)
      connectLockstep(nh);
    else
      timer_ = nh.createWallTimer(ros::WallDuration(0.01), [this](const ros::WallTimerEvent&) { onTimer(); });
    const RadioParams& p = o_.radio;
    ROS_INFO(
        "comm_broker: %zu robots, B %.0f kB/s, d_init %.0f m, d_intf %.0f m, P_max %.2f, seed %s, sizes %s, "
        "timeout %s%s",
        o_.robots.size(), p.bandwidth_kBps, p.d_init, p.d_intf, p.p_max,
        o_.lockstep ? "from the sequence" : std::to_string(o_.seed).c_str(), toString(p.size_model).c_str(),
        toString(p.timeout_mode).c_str(), o_.lockstep ? ", lockstep (driven by the player)" : "");
  }

  ~CommBroker() { writeLog(); }

  void writeLog() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (o_.log_file.empty()) return;
    try {
      writeTransferLog(o_.log_file, sim_->transferLog(), sim_->stats(), sim_->params());
    } catch (const std::exception& e) { ROS_ERROR("comm_broker: %s", e.what()); }
  }

 private:
  /// What a delivery carries besides the scan (which the payload store holds).
  struct Stored {
    std_msgs::Header header;
    geometry_msgs::Pose reference;
    bool has_reference = false;
  };

  void connectRobots(ros::NodeHandle& nh) {
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
  }

  void connectLockstep(ros::NodeHandle& nh) {
    sequence_sub_ = nh.subscribe<cosmo::TeamSequence>(
        ros_glue::kTeamSequenceTopic, 1, [this](const cosmo::TeamSequence::ConstPtr& m) { onSequence(*m); });
    for (char r : sim_->robots())
      trajectory_subs_.push_back(nh.subscribe<cosmo::ReferenceTrajectory>(
          ros_glue::referenceTrajectoryTopic(r), 1,
          [this, r](const cosmo::ReferenceTrajectory::ConstPtr& m) { onTrajectory(r, *m); }));
    step_done_pub_ = nh.advertise<cosmo::RadioStepDone>("comm/step_done", 100);
    step_request_sub_ = nh.subscribe<cosmo::RadioStepRequest>(
        "comm/step_request", 100, [this](const cosmo::RadioStepRequest::ConstPtr& m) { onStepRequest(*m); });
  }

  /// Decode and pack (xz, outside the lock), then the offer to the radio.
  void onKeyframe(char r, const cosmo::Keyframe& m) {
    const std::string topic = std::string("/") + r + "/keyframe_scans";
    if (!m.robot.empty() && m.robot != std::string(1, r))
      ROS_WARN_THROTTLE(5.0, "comm_broker: %s: message says robot '%s'; using '%c'", topic.c_str(), m.robot.c_str(), r);
    PayloadStore::Payload payload;
    try {
      auto scan = std::make_shared<Scan>();  // only x y z travel
      scan->points = ros_glue::fromPointCloud2(m.cloud, true, topic).points;
      payload = payloads_.pack(std::move(scan));
    } catch (const std::exception& e) {
      ROS_ERROR("comm_broker: dropping keyframe %u: %s", m.index, e.what());
      std::lock_guard<std::mutex> lock(mutex_);
      steps_.offerArrived(r);  // counted, so that a lockstep step waiting for it goes on
      runPendingSteps();
      return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    offer(r, m, std::move(payload));
    runPendingSteps();
  }

  // With the mutex held.
  void offer(char r, const cosmo::Keyframe& m, PayloadStore::Payload payload) {
    const PayloadStore::Sizes sizes = payloads_.store(r, m.index, std::move(payload));
    sim_->offerKeyframe(r, m.index, sizes.payload, sizes.raw);
    if (o_.lockstep && !steps_.started()) early_offers_.push_back({r, m.index, sizes});  // offered again once seeded
    Stored& s = store_[{r, m.index}];
    s.header = m.header;
    s.header.frame_id = m.header.frame_id.empty() ? m.cloud.header.frame_id : m.header.frame_id;
    s.reference = m.reference;
    s.has_reference = m.has_reference;
    steps_.offerArrived(r);
  }

  void onPose(char r, const geometry_msgs::PoseStamped& m) {
    const Eigen::Vector3d p(m.pose.position.x, m.pose.position.y, m.pose.position.z);
    std::lock_guard<std::mutex> lock(mutex_);
    if (o_.lockstep) {  // positions from the sequence's references; kept for robots without one
      last_position_[r] = p;
    } else if (!p.allFinite()) {
      ROS_WARN_THROTTLE(5.0, "comm_broker: /%c/reference_pose: non-finite position ignored", r);
    } else {
      sim_->setRobotState(r, p, true);
    }
  }

  /// Real time: every step of the grid up to ROS time now, catching up when time jumps.
  void onTimer() {
    const ros::Time now_ros = ros::Time::now();
    if (now_ros.isZero()) return;  // sim time before the first /clock
    const double now = now_ros.toSec();
    std::lock_guard<std::mutex> lock(mutex_);
    alignStepGrid(now);
    Links links;  // links of this batch of steps
    double t_last = 0.0;
    int steps = 0;
    while (sim_->nextStepTime() <= now + 1e-9) {
      t_last = sim_->nextStepTime();
      for (const Transfer& x : sim_->step(t_last)) deliver(x, ros::Time(t_last));
      for (const auto& [pair, c] : lastStepLinks(*sim_)) links[pair] = c;
      ++steps;
    }
    if (steps == 0) return;
    publishRadioState(now_ros, t_last, t_last, links);
  }

  // With the mutex held: the grid starts at the first ROS time seen, and again after a jump of over an hour.
  void alignStepGrid(double now) {
    const double dt = sim_->params().step;
    if (!started_ || now - sim_->nextStepTime() > 3600.0) {
      if (started_) ROS_WARN("comm_broker: ROS time jumped forward by more than an hour; restarting the step grid");
      sim_->setStartTime(std::ceil(now / dt - 1e-9) * dt);
      started_ = true;
    } else if (sim_->nextStepTime() - now > 1.0) {
      ROS_WARN_THROTTLE(5.0, "comm_broker: ROS time went backwards (%.3f s < %.3f s); waiting", now,
                        sim_->nextStepTime());
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
        references_[r] = Trajectory{};
      }
    startLockstep();
  }

  void onTrajectory(char r, const cosmo::ReferenceTrajectory& m) {
    Trajectory reference;
    try {
      reference = ros_glue::trajectoryFromMsg(m, ros_glue::referenceTrajectoryTopic(r));
    } catch (const std::exception& e) { ROS_ERROR("comm_broker: %s; positions from its reference_pose", e.what()); }
    std::lock_guard<std::mutex> lock(mutex_);
    references_[r] = std::move(reference);
    startLockstep();
  }

  // Lockstep, with the mutex held, once the sequence and every reference arrived: grid origin and radio seed as
  // the offline driver's, the front-ends connected; then the requests waiting for it run.
  void startLockstep() {
    if (steps_.started() || !sequence_) return;
    for (char r : sim_->robots())
      if (!references_.count(r)) return;
    waitForFrontends();
    origin_ = pipeline::radioGridOrigin(sequence_->start.toNSec(), sim_->params().step);
    const std::uint64_t seed = pipeline::deriveSeed(sequence_->seed, "radio");
    sim_ = std::make_unique<RadioSimulator>(sim_->params(), sim_->robots(), seed);
    for (const auto& o : early_offers_) sim_->offerKeyframe(o.robot, o.index, o.sizes.payload, o.sizes.raw);
    early_offers_.clear();
    steps_.start();
    ROS_INFO("comm_broker: lockstep on sequence %s (seed %llu): radio seed %llu, grid origin %.3f s",
             sequence_->name.c_str(), static_cast<unsigned long long>(sequence_->seed),
             static_cast<unsigned long long>(seed), toSeconds(origin_));
    runPendingSteps();
  }

  // Every front-end's offers and deliveries connected (a message sent before its connection exists is lost).
  void waitForFrontends() {
    const auto connected = [&] {
      for (const auto& sub : keyframe_subs_)
        if (sub.getNumPublishers() == 0) return false;
      for (const auto& [r, pub] : received_pubs_)
        if (pub.getNumSubscribers() == 0) return false;
      return true;
    };
    if (!ros_glue::waitUntil(connected, ros_glue::wallDeadline(30.0)))
      ROS_WARN("comm_broker: lockstep: not every front-end is connected; going on");
  }

  void onStepRequest(const cosmo::RadioStepRequest& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    steps_.push(stepFromMsg(m));
    runPendingSteps();
  }

  // Lockstep, with the mutex held: the pending requests, in order, whose keyframe offers all arrived.
  void runPendingSteps() {
    while (const std::optional<pipeline::QueuedRadioStep> request = steps_.popReady()) runStep(*request);
  }

  /// The radio through the request's stamp (pipeline::advanceRadio, TeamRun's rule), then the answer.
  void runStep(const pipeline::QueuedRadioStep& request) {
    StampNs last_step = 0;
    const auto state = [&](char r, StampNs step_stamp) {
      last_step = step_stamp;
      pipeline::RadioRobotState s;
      s.on = request.on(r);
      const auto last = last_position_.find(r);
      s.position = pipeline::radioPosition(references_[r], step_stamp,
                                           last == last_position_.end() ? Eigen::Vector3d::Zero() : last->second);
      return s;
    };
    const auto on_transfer = [&](StampNs step_stamp, const Transfer& x) {
      deliver(x, ros_glue::stampToRos(step_stamp));
    };
    if (pipeline::advanceRadio(*sim_, origin_, request.order.through, state, on_transfer) > 0) {
      publishRadioState(ros_glue::stampToRos(last_step), toSeconds(last_step - origin_), toSeconds(last_step),
                        lastStepLinks(*sim_));
      last_step_ = last_step;
    }
    step_done_pub_.publish(stepDoneMsg(request.seq));
  }

  cosmo::RadioStepDone stepDoneMsg(std::uint32_t seq) {
    cosmo::RadioStepDone done;
    done.seq = seq;
    done.stamp = ros_glue::stampToRos(last_step_);
    done.next_stamp = ros_glue::stampToRos(pipeline::nextRadioStepStamp(*sim_, origin_));
    for (char r : sim_->robots()) {
      done.robots.push_back(r);
      done.delivered.push_back(delivered_[r]);
    }
    return done;
  }

  // Called with the mutex held. `when`: the step the transfer ended in.
  void deliver(const Transfer& x, const ros::Time& when) {
    if (x.outcome != Transfer::Outcome::Delivered) {
      ROS_DEBUG("comm_broker: %c -> %c keyframe %zu timed out", x.sender, x.receiver, x.keyframe);
      return;
    }
    const auto it = store_.find({x.sender, x.keyframe});
    if (it == store_.end()) return;
    const Stored& s = it->second;
    cosmo::Keyframe out;
    try {
      out.cloud = ros_glue::toPointCloud2(*payloads_.deliver(x.sender, x.keyframe), s.header.frame_id);
    } catch (const std::exception& e) {
      ROS_ERROR("comm_broker: keyframe %c%zu: %s", x.sender, x.keyframe, e.what());
      return;
    }
    out.header = s.header;
    out.cloud.header = s.header;
    out.robot = out.sender = std::string(1, x.sender);
    out.index = static_cast<std::uint32_t>(x.keyframe);
    out.reference = s.reference;
    out.has_reference = s.has_reference;
    out.received_at = when;
    received_pubs_.at(x.receiver).publish(out);
    ++delivered_[x.receiver];
    ROS_DEBUG("comm_broker: delivered %c%zu to %c (%zu bytes, %.1f s)", x.sender, x.keyframe, x.receiver, x.bytes,
              x.end - x.start);
  }

  /// After a batch of steps, the latest at `radio_time`: link markers, /comm/stats (at `stats_time`), the log.
  void publishRadioState(const ros::Time& stamp, double radio_time, double stats_time, const Links& links) {
    links_pub_.publish(ros_glue::linkMarkers(*sim_, links, radio_time, o_.frame_id, stamp));
    std_msgs::String stats;
    stats.data = radioStatus(*sim_, stats_time).dump();
    stats_pub_.publish(stats);
    writeLogEvery30s(radio_time);
  }

  /// The transfer log (CSV + summary) rewritten when 30 s of radio time passed since the last write.
  void writeLogEvery30s(double radio_time) {
    if (o_.log_file.empty() || radio_time - last_log_write_ < 30.0) return;
    last_log_write_ = radio_time;
    try {
      writeTransferLog(o_.log_file, sim_->transferLog(), sim_->stats(), sim_->params());
    } catch (const std::exception& ex) { ROS_ERROR_THROTTLE(30.0, "comm_broker: %s", ex.what()); }
  }

  struct Offer {
    char robot;
    std::uint32_t index;
    PayloadStore::Sizes sizes;
  };

  Options o_;
  std::mutex mutex_;
  std::unique_ptr<RadioSimulator> sim_;
  PayloadStore payloads_;
  std::map<std::pair<char, std::size_t>, Stored> store_;
  std::map<char, std::uint32_t> delivered_;
  bool started_ = false;  ///< real time: the step grid is aligned
  double last_log_write_ = 0.0;
  // lockstep
  pipeline::RadioStepQueue steps_;
  StampNs origin_ = 0, last_step_ = 0;
  std::map<char, Trajectory> references_;  ///< from the player, one per robot (empty: none)
  std::optional<cosmo::TeamSequence> sequence_;
  std::vector<Offer> early_offers_;  ///< offers before the sequence arrived (the radio is re-seeded then)
  std::map<char, Eigen::Vector3d> last_position_;
  ros::WallTimer timer_;
  std::vector<ros::Subscriber> keyframe_subs_, pose_subs_, trajectory_subs_;
  std::map<char, ros::Publisher> received_pubs_;
  ros::Subscriber sequence_sub_, step_request_sub_;
  ros::Publisher links_pub_, stats_pub_, step_done_pub_;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "comm_broker");
  return ros_glue::runNode("comm_broker", [] {
    ros::NodeHandle nh, pnh("~");
    CommBroker broker(nh, readOptions(pnh));
    ros::AsyncSpinner spinner(2);  // compression of offered scans does not hold up the steps
    spinner.start();
    ros::waitForShutdown();
    spinner.stop();
    broker.writeLog();
  });
}
