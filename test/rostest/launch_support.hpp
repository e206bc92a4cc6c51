#pragma once
// What the launch rostests share: the package's programs beside the test binary, the offline driver's JRL for the
// same settings (the uninterrupted run's bytes: the lockstep launch writes the same, sequence.test checks it),
// waiting on a latched topic, a node's process id (to SIGKILL it), and the first difference of two files.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "cosmo/ros/peer_probe.hpp"
#include "cosmo/common/whole_file.hpp"

namespace cosmo::test {

inline std::string siblingProgram(const std::string& name) {
  char exe[4096] = {0};
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n > 0) {
    const auto p = std::filesystem::path(std::string(exe, n)).parent_path() / name;
    if (std::filesystem::exists(p)) return p.string();
  }
  return name;
}

inline std::string shellQuote(const std::string& s) { return "'" + s + "'"; }

/// Spins until `done` holds or `seconds` of wall time passed; returns whether it holds.
inline bool spinUntil(const std::function<bool()>& done, double seconds) {
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::ok() && !done() && ros::WallTime::now() < until) {
    ros::spinOnce();
    ros::WallDuration(0.02).sleep();
  }
  return done();
}

/// The process id of `node` (0 when it does not answer).
inline int pidOf(const std::string& node) {
  const live::PeerProbe probe = ros_glue::probePeer(node, 2.0);
  return probe.answered ? probe.pid : 0;
}

/// The settings of the launch under test, from the parameters the .test file sets and the player resolved.
struct OfflineRun {
  std::string sequence, seed, comm, odometry, noise_models, config_dir;
  double max_seconds = 0.0;
  static OfflineRun fromParams() {
    ros::NodeHandle nh;
    OfflineRun r;
    nh.getParam("/player/resolved_sequence", r.sequence);
    nh.getParam("/player/resolved_seed", r.seed);
    nh.param<std::string>("/comm", r.comm, "wifi");
    nh.param<std::string>("/odometry", r.odometry, "reference");
    nh.getParam("/noise_models", r.noise_models);
    nh.getParam("/config_dir", r.config_dir);
    nh.param("/max_seconds", r.max_seconds, 0.0);
    return r;
  }
  /// Runs cosmo_generate into `out_dir`; returns the path of its JRL named like `jrl_name`, empty on failure (with
  /// a test failure naming the command).
  std::string run(const std::string& out_dir, const std::string& jrl_name) const {
    std::filesystem::remove_all(out_dir);
    std::ostringstream cmd;
    cmd << shellQuote(siblingProgram("cosmo_generate")) << " " << shellQuote(sequence) << " --seed " << seed
        << " --comm " << comm << " --config-dir " << shellQuote(config_dir) << " --noise-models "
        << shellQuote(noise_models) << " --out " << shellQuote(out_dir) << " --quiet"
        << (odometry == "reference" ? " --odometry reference" : "");
    if (max_seconds > 0) cmd << " --max-seconds " << max_seconds;
    cmd << " > " << shellQuote(out_dir + ".log") << " 2>&1";
    const ros::WallTime start = ros::WallTime::now();
    if (std::system(cmd.str().c_str()) != 0) {
      ADD_FAILURE() << "failed: " << cmd.str();
      return "";
    }
    std::cout << "cosmo_generate: " << (ros::WallTime::now() - start).toSec() << " s wall" << std::endl;
    return out_dir + "/" + jrl_name;
  }
};

/// Empty when the two files hold the same bytes, else where they first differ, with the text around it.
inline std::string firstDifference(const std::string& a_path, const std::string& b_path) {
  const std::string a = cosmo::readWholeFileOrEmpty(a_path), b = cosmo::readWholeFileOrEmpty(b_path);
  if (a == b) return "";
  std::size_t at = 0;
  while (at < a.size() && at < b.size() && a[at] == b[at]) ++at;
  const std::size_t line = 1 + static_cast<std::size_t>(std::count(a.begin(), a.begin() + at, '\n'));
  const std::size_t from = at > 200 ? at - 200 : 0;
  std::ostringstream out;
  out << a_path << " (" << a.size() << " bytes) vs " << b_path << " (" << b.size() << " bytes) differ first at byte "
      << at << " (line " << line << "):\n  " << a.substr(from, 400) << "\n  " << b.substr(from, 400);
  return out.str();
}

}  // namespace cosmo::test
