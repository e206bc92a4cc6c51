#pragma once
// A front-end's scan input. Real time (capacity > 0): the points topic is served by its own thread, which only
// pushes each scan into a bounded frontend::ScanQueue (the oldest waiting scan is skipped when it is full); the
// scans are handed, one per callback, to `on_scan` on the node's own callback queue (ros::spin), between the other
// callbacks. Lockstep (capacity 0): `on_scan` is called directly by the subscriber (the player waits for every scan).
#include <atomic>
#include <functional>
#include <memory>
#include <string>

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>

#include "cosmo/frontend/scan_queue.hpp"

namespace cosmo::ros_glue {

class ScanInput {
 public:
  using Scan = sensor_msgs::PointCloud2::ConstPtr;
  /// `held`: scans wait (and the oldest are skipped when full) until resume().
  ScanInput(ros::NodeHandle& nh, const std::string& topic, std::size_t capacity, std::function<void(const Scan&)> on_scan,
            bool held = false);
  ~ScanInput();
  ScanInput(const ScanInput&) = delete;
  ScanInput& operator=(const ScanInput&) = delete;

  void resume();
  std::size_t queued() const { return queue_.size(); }
  std::size_t skipped() const { return queue_.skipped(); }
  std::size_t peak() const { return queue_.peak(); }
  std::string topic() const { return sub_.getTopic(); }

 private:
  class Drain;
  void push(const Scan& scan);
  void schedule();
  void drainOne();

  std::function<void(const Scan&)> on_scan_;
  frontend::ScanQueue<Scan> queue_;
  std::atomic<bool> held_, scheduled_{false};
  ros::CallbackQueue own_queue_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
  ros::Subscriber sub_;
};

}  // namespace cosmo::ros_glue
