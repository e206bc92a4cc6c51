#include "cosmo/ros/scan_input.hpp"

#include <boost/make_shared.hpp>

namespace cosmo::ros_glue {

/// One hand-over, queued on the node's callback queue.
class ScanInput::Drain : public ros::CallbackInterface {
 public:
  explicit Drain(ScanInput* input) : input_(input) {}
  CallResult call() override {
    input_->drainOne();
    return Success;
  }

 private:
  ScanInput* input_;
};

ScanInput::ScanInput(ros::NodeHandle& nh, const std::string& topic, std::size_t capacity,
                     std::function<void(const Scan&)> on_scan, bool held)
    : on_scan_(std::move(on_scan)), queue_(capacity), held_(held) {
  if (capacity == 0) {
    sub_ = nh.subscribe<sensor_msgs::PointCloud2>(topic, 5, [this](const Scan& m) { on_scan_(m); });
    return;
  }
  ros::SubscribeOptions options = ros::SubscribeOptions::create<sensor_msgs::PointCloud2>(
      topic, 100, [this](const Scan& m) { push(m); }, ros::VoidPtr(), &own_queue_);
  sub_ = nh.subscribe(options);
  spinner_ = std::make_unique<ros::AsyncSpinner>(1, &own_queue_);
  spinner_->start();
}

ScanInput::~ScanInput() {
  if (spinner_) spinner_->stop();
  sub_.shutdown();
  ros::getGlobalCallbackQueue()->removeByID(reinterpret_cast<uint64_t>(this));
}

void ScanInput::resume() {
  held_ = false;
  schedule();
}

void ScanInput::push(const Scan& scan) {
  queue_.push(scan);
  if (!held_) schedule();
}

void ScanInput::schedule() {
  if (!scheduled_.exchange(true))
    ros::getGlobalCallbackQueue()->addCallback(boost::make_shared<Drain>(this), reinterpret_cast<uint64_t>(this));
}

void ScanInput::drainOne() {
  scheduled_ = false;
  if (held_) return;
  const std::optional<Scan> scan = queue_.pop();
  if (!scan) return;
  on_scan_(*scan);
  if (queue_.size() > 0) schedule();
}

}  // namespace cosmo::ros_glue
