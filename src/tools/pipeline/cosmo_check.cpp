// cosmo_check: the pre-flight check of a sequence config. Reads the first scans of every trial and its reference
// and prints one line per trial (bag, topic, point fields, rate, stamp convention, invalid returns, reference span
// against the scans, reference rate, extrinsic rotation, noise models), then the verdict. Exit 0 when the run can
// produce a labelled dataset, 1 with the reasons when it cannot, 2 on a usage error. cosmo_generate and the
// player run the same check first.
//
//   cosmo_check SEQUENCE.yaml [--data-root DIR] [--config-dir DIR] [--noise-models FILE]
#include <cstdio>
#include <optional>
#include <string>

#include "cosmo/common/command_line.hpp"
#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/trials/sequence_resolution.hpp"
#include "cosmo/trials/trial_probe.hpp"

using namespace cosmo;

namespace {

struct Args {
  std::string sequence, data_root, config_dir = cosmo::defaultConfigDir(), noise;
};

/// The command line; an exit code when the program ends here (help, a usage error).
std::optional<int> parseArgs(int argc, char** argv, Args& args) {
  CommandLine app("cosmo_check",
                  "The pre-flight check of a sequence config: one line per trial, then the verdict. Exit 0: the run "
                  "can produce a labelled dataset; 1: it cannot (the reasons are printed); 2: a usage error.");
  addSequence(app, args.sequence, args.data_root);
  app.add_option("--config-dir", args.config_dir,
                 "where noise_models/<environment>.yaml is looked up (default: the source tree's config/)")
      ->type_name("DIR");
  app.add_option("--noise-models", args.noise, "the noise-model file the run would be given")->type_name("FILE");
  return app.parseOrExit(argc, argv);
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (const auto code = parseArgs(argc, argv, args)) return *code;
  try {
    trials::SequenceChoice choice;  // as the run would resolve it (trials/sequence_resolution.hpp)
    choice.sequence = args.sequence;
    choice.data_root = args.data_root;
    choice.config_dir = args.config_dir;
    choice.noise_models = args.noise;
    const sequence::SequenceConfig config = trials::loadSequence(choice);
    std::string text;
    const bool ok = trials::checkSequence(config, trials::noiseModelsSource(choice, config), text);
    std::printf("%s", text.c_str());
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::printf("cannot produce a labelled dataset: %s\n", e.what());
    return 1;
  }
}
