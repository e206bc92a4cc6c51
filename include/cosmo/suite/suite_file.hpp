#pragma once
// A suite file (config/suites/*.yaml): the datasets of a benchmark in one place. Format:
//
//   name: cosmo_bench                 # the report's title
//   comm: [wifi, proradio]            # comm models; a sequence's models share one odometry pass
//   max_seconds: 0                    # optional: stop each run after this much sequence time (0: whole)
//   config_dir: ..                    # optional: cosmo_generate --config-dir (relative to this file)
//   sequences:                        # one entry per sequence; paths relative to this file
//     - sequence: ../sequences/ntu_r3_00.yaml
//       data_root: mcd                # optional: the trials' folder, relative to --data-root
//       label: ntu_r3_00              # optional: the datasets' name prefix (default: the sequence's name)
//     - simulate: ../sim/suite_ci.yaml   # a synthetic sequence, made (and cached) by cosmo_simulate
//       layout: mcd                   # cosmo | mcd | cu-multi
//   noise_models:                     # estimated first, each a job of its own (spec section 6)
//     - estimate: cu_boulder          # the file <out>/noise_models/cu_boulder/cu_boulder.yaml
//       from: kittredge_loop          # a sequence's label
//       trial: c                      # robot id or trial name, run alone through the front-end
//       for: [kittredge_loop, main_campus]   # optional: default the sequences of environment `estimate`
//       why: "..."                    # optional: the reason, for the report
//   variants:                         # every combination of the listed values (variant_keys.hpp)
//     seed: [1, 2]
//
// Every key is checked when the file is read: an unknown one stops with the file, the key and the nearest name.
#include <string>
#include <vector>

#include "cosmo/suite/variant_keys.hpp"

namespace cosmo::suite {

struct SequenceEntry {
  std::string label;      ///< unique in the suite: the datasets' names start with it ("" until resolved)
  std::string sequence;   ///< absolute path of a sequence config (a `sequence:` entry)
  std::string simulate;   ///< absolute path of a cosmo_simulate config (a `simulate:` entry)
  std::string layout = "cosmo";
  std::string data_root;  ///< relative to the command's --data-root (or absolute); `sequence:` entries only
  std::string where;      ///< "<file>: sequences[i]"
};

struct EstimateEntry {
  std::string name;  ///< the environment the models are for
  std::string from;  ///< a sequence entry's label
  std::string trial;
  std::vector<std::string> used_by;  ///< labels; empty: the sequences whose environment is `name`
  std::string why;
  std::string where;
};

/// One `variants:` key and its values, in the file's order.
struct VariantAxis {
  std::string key;
  std::vector<VariantValue> values;
};

struct SuiteFile {
  std::string path;  ///< absolute
  std::string name;
  std::vector<std::string> comms{"wifi"};
  double max_seconds = 0.0;
  std::string config_dir;  ///< absolute; "" = cosmo_generate's default
  std::vector<SequenceEntry> sequences;
  std::vector<EstimateEntry> estimates;
  std::vector<VariantAxis> variants;

  /// Reads and checks a suite file; throws std::runtime_error naming the file and key.
  static SuiteFile load(const std::string& path);
};

}  // namespace cosmo::suite
