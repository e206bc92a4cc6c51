// cosmo_check: the pre-flight check of a sequence config. Reads the first scans of every trial and its reference
// and prints one line per trial (bag, topic, point fields, rate, stamp convention, invalid returns, reference span
// against the scans, reference rate, extrinsic rotation, noise models), then the verdict. Exit 0 when the run can
// produce a labelled dataset, 1 with the reasons when it cannot, 2 on a usage error. cosmo_generate and the
// player run the same check first.
//
//   cosmo_check SEQUENCE.yaml [--data-root DIR] [--config-dir DIR] [--noise-models FILE]
#include <cstdio>
#include <iostream>
#include <string>

#include "cosmo/pipeline/frontend_params.hpp"
#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/pipeline/sequence_noise_models.hpp"
#include "cosmo/ros/trial_probe.hpp"

using namespace cosmo;

namespace {
void usage() {
  std::cerr << "usage: cosmo_check SEQUENCE.yaml [--data-root DIR] [--config-dir DIR] [--noise-models FILE]\n"
               "  --data-root DIR      the folder the trials' bags and references are below (default: the config's\n"
               "                       data_root key, else $COSMO_DATA_ROOT, else the config's folder)\n"
               "  --config-dir DIR     where noise_models/<environment>.yaml is looked up (default: the source tree's "
               "config/)\n"
               "  --noise-models FILE  the noise-model file the run would be given\n"
               "exit 0: the run can produce a labelled dataset; 1: it cannot (the reasons are printed)\n";
}
}  // namespace

int main(int argc, char** argv) {
  std::string sequence, data_root, config_dir = pipeline::defaultConfigDir(), noise;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if ((a == "--data-root" || a == "--config-dir" || a == "--noise-models") && !has_value) {
      std::cerr << a << " needs a value\n";
      usage();
      return 2;
    }
    if (a == "--data-root")
      data_root = argv[++i];
    else if (a == "--config-dir")
      config_dir = argv[++i];
    else if (a == "--noise-models")
      noise = argv[++i];
    else if (a == "-h" || a == "--help") {
      usage();
      return 0;
    } else if (!a.empty() && a[0] == '-') {
      std::cerr << "unknown option " << a << "\n";
      usage();
      return 2;
    } else if (sequence.empty())
      sequence = a;
    else {
      std::cerr << "unexpected argument " << a << "\n";
      usage();
      return 2;
    }
  }
  if (sequence.empty()) {
    usage();
    return 2;
  }
  try {
    const pipeline::SequenceConfig config = pipeline::SequenceConfig::load(sequence, data_root);
    std::string text;
    const bool ok = ros_glue::checkSequence(config, pipeline::chooseNoiseModels(config, config_dir, noise), text);
    std::printf("%s", text.c_str());
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::printf("cannot produce a labelled dataset: %s\n", e.what());
    return 1;
  }
}
