#pragma once
// Parameters of one robot's front-end (spec section 4): its own keys in config/frontend.yaml plus the module
// parameters it composes (config/odometry.yaml, place_recognition.yaml, registration.yaml).
#include <string>

#include "cosmo/common/config.hpp"
#include "cosmo/common/config_dir.hpp"
#include "cosmo/odometry/loam_params.hpp"
#include "cosmo/frontend/odometry_source.hpp"
#include "cosmo/place_recognition/place_recognizer.hpp"
#include "cosmo/registration/registration_params.hpp"

namespace cosmo::frontend {

struct FrontendParams {
  /// d_kf (m): a keyframe when the integrated odometry since the last one exceeds this (spec 4.2).
  double keyframe_distance = 2.0;
  /// Dewarp keyframe scans with the reference trajectory when the robot has one (spec 4.3); else odometry.
  bool dewarp_with_reference = true;
  /// Points closer than this (m) are dropped from the keyframe scans kept, offered and registered (0 = keep).
  double keyframe_min_range = 0.0;
  /// A keyframe's reference pose is taken from the reference trajectory when the stamp lies inside it or at
  /// most this many seconds outside it (held at the nearest end); farther out the keyframe has none.
  double reference_tolerance_s = 1.0;
  /// Keep the registration features of every keyframe / received scan once computed (faster, more memory).
  bool cache_features = true;
  /// Keep the keyframe scans (own and received) and their features in a spill file instead of memory; only what is
  /// in use stays in memory (kept_scan.hpp). The results are the same bit for bit; the memory no longer grows with
  /// the keyframes (about 1.5 MB per keyframe at 64 beams otherwise), the disk does while the process runs.
  bool spill_keyframes = true;
  /// Folder of the spill file (empty: the system's temp folder, TMPDIR).
  std::string spill_dir;
  /// Which odometry the scans get (odometry_source.hpp): the drivers' one key (the node's ~odometry,
  /// cosmo_generate's --odometry), not a key of frontend.yaml.
  OdometryKind odometry = OdometryKind::Loam;

  odometry::LoamParams loam;
  place_recognition::PlaceRecognitionParams place;
  registration::RegistrationParams registration;

  /// The front-end's own keys (root or `frontend` section of config/frontend.yaml).
  static FrontendParams fromConfig(const ConfigNode& node);
  /// Every file of a config folder that exists: frontend.yaml, odometry.yaml, place_recognition.yaml,
  /// registration.yaml (a missing file keeps the defaults).
  static FrontendParams loadDir(const std::string& config_dir);

  /// The YAML keys, one per member (common/param_list.hpp).
  template <class Visitor>
  void visit(Visitor&& v) {
    v("keyframe_distance", keyframe_distance);
    v("dewarp_with_reference", dewarp_with_reference);
    v("keyframe_min_range", keyframe_min_range);
    v("reference_tolerance_s", reference_tolerance_s);
    v("cache_features", cache_features);
    v("spill_keyframes", spill_keyframes);
    v("spill_dir", spill_dir);
  }
};

}  // namespace cosmo::frontend
