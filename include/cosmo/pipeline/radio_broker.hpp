#pragma once
// The comm_broker's radio without ROS: the RadioSimulator, the PayloadStore of the offered keyframe scans and the
// step bookkeeping, in one of two modes.
// - Lockstep (the player drives the steps): requests (RadioStepQueue) run in order once the radio is started and
//   the offers they name arrived. The radio starts when the player's sequence and every robot's reference arrived:
//   grid origin radioGridOrigin(sequence start) and seed deriveSeed(sequence seed, "radio"), as TeamRun's; offers
//   made before are offered again to the re-seeded radio. Each request runs advanceRadio (team_radio.hpp, the
//   rule TeamRun runs) with the robots on as the request says and their positions from their references
//   (radioPosition; without one, the last reported position).
// - Real time: every step of the grid up to a given time; the grid starts at the first time seen, and again after
//   a jump of over an hour; positions are set as they are reported.
// A delivered transfer reaches the caller with the scan the receiver gets (PayloadStore::deliver); the caller
// says whether it handed it over, which counts it as delivered to that receiver. Not thread-safe: the caller
// serialises calls (pack() changes nothing and may run outside the caller's lock).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "cosmo/comm/payload_store.hpp"
#include "cosmo/comm/radio_simulator.hpp"
#include "cosmo/common/time.hpp"
#include "cosmo/common/trajectory.hpp"
#include "cosmo/pipeline/radio_step_queue.hpp"

namespace cosmo::pipeline {

class RadioBroker {
 public:
  using Links = std::map<std::pair<char, char>, comm::ActiveCommunication>;

  /// A transfer that ended in a step.
  struct Delivery {
    const comm::Transfer& transfer;
    double step_time = 0.0;            ///< radio time of the step (s)
    StampNs step_stamp = 0;            ///< lockstep: sequence stamp of the step
    std::shared_ptr<const Scan> scan;  ///< delivered: what the receiver gets (nullptr: never offered)
    std::string error;                 ///< delivered, but its payload does not decompress
    bool delivered() const { return transfer.outcome == comm::Transfer::Outcome::Delivered; }
  };
  /// Returns whether the delivery was handed to its receiver (counted in delivered()).
  using DeliveryFn = std::function<bool(const Delivery&)>;

  /// A lockstep request answered.
  struct StepDone {
    std::uint32_t seq = 0;
    std::size_t steps = 0;  ///< radio steps the request ran
    StampNs last_step = 0;  ///< the latest step run so far (sequence time)
    StampNs next_step = 0;  ///< nextRadioStepStamp: a scan stamped at or after it needs a step first
    std::map<char, std::uint32_t> delivered;
  };
  using StepDoneFn = std::function<void(const StepDone&)>;

  /// A batch of real-time steps.
  struct StepBatch {
    std::size_t steps = 0;
    double last_time = 0.0;       ///< radio time of the latest step
    Links links;                  ///< the links of the batch's steps (the latest per pair)
    bool grid_restarted = false;  ///< time jumped forward by over an hour: the grid restarted
    bool time_went_back = false;  ///< time is over 1 s behind the next step: nothing ran
  };

  RadioBroker(const comm::RadioParams& params, std::vector<char> robots, std::uint64_t seed, bool lockstep,
              bool compress, std::uint32_t xz_preset);

  // Offers.
  comm::PayloadStore::Payload pack(std::shared_ptr<const Scan> scan) const { return payloads_.pack(std::move(scan)); }
  void offer(char robot, std::uint32_t index, comm::PayloadStore::Payload payload);
  /// An offer that could not be packed: a request waiting for it goes on.
  void offerDropped(char robot) { steps_.offerArrived(robot); }
  /// A reported position: in lockstep the fallback for a robot without a reference, in real time its state (on).
  /// False when it is not finite (ignored in real time).
  bool positionReported(char robot, const Eigen::Vector3d& position);

  // Lockstep.
  /// The player's sequence; returns the team's robots it does not name (their positions: the reported ones).
  std::vector<char> setSequence(StampNs start, std::uint64_t sequence_seed, const std::vector<char>& sequence_robots);
  void setReference(char robot, Trajectory reference);
  /// The sequence and every robot's reference arrived, and the radio is not started yet.
  bool readyToStart() const;
  /// Starts the radio (readyToStart() must hold); returns the radio's seed.
  std::uint64_t start();
  bool started() const { return steps_.started(); }
  StampNs origin() const { return origin_; }
  void request(QueuedRadioStep step) { steps_.push(std::move(step)); }
  /// Runs the requests that are ready, in order: their deliveries, then their answer.
  void runReadySteps(const DeliveryFn& on_delivery, const StepDoneFn& on_done);

  // Real time.
  /// Every step of the grid up to radio time `now` (s).
  StepBatch stepRealTime(double now, const DeliveryFn& on_delivery);

  const comm::RadioSimulator& radio() const { return *radio_; }
  /// Scans handed to each receiver so far.
  const std::map<char, std::uint32_t>& delivered() const { return delivered_; }
  /// Per robot, 1 + the highest keyframe index it offered (a restarted front-end numbers its keyframes after it).
  const std::map<char, std::uint32_t>& nextIndex() const { return next_index_; }

 private:
  struct EarlyOffer {
    char robot;
    std::uint32_t index;
    comm::PayloadStore::Sizes sizes;
  };

  StepDone runStep(const QueuedRadioStep& request, const DeliveryFn& on_delivery);
  void deliver(const comm::Transfer& transfer, double step_time, StampNs step_stamp, const DeliveryFn& on_delivery);

  bool lockstep_;
  std::unique_ptr<comm::RadioSimulator> radio_;
  comm::PayloadStore payloads_;
  std::map<char, std::uint32_t> delivered_;
  std::map<char, std::uint32_t> next_index_;
  // lockstep
  RadioStepQueue steps_;
  std::optional<std::pair<StampNs, std::uint64_t>> sequence_;  ///< start, seed
  std::map<char, Trajectory> references_;                      ///< one per robot (empty: none)
  std::map<char, Eigen::Vector3d> last_position_;
  std::vector<EarlyOffer> early_offers_;  ///< offered before the start (the radio is re-seeded then)
  StampNs origin_ = 0, last_step_ = 0;
  // real time
  bool grid_started_ = false;
};

}  // namespace cosmo::pipeline
