// A sequence config (config/sequences/*.yaml, the layouts' configs written by cosmo_simulate), read and checked
// as every driver reads it, with the registration keys it sets merged over the compiled-in defaults.
#include "../fuzz_target.hpp"
#include "../input_file.hpp"
#include "cosmo/sequence/sequence_config.hpp"

using namespace cosmo;

COSMO_FUZZ_TARGET(sequence_yaml) {
  const std::string path = fuzz::inputFile(data, size, "sequence.yaml");
  const sequence::SequenceConfig config = sequence::SequenceConfig::load(path, fuzz::scratchDir().string());
  for (char robot : config.robots()) config.trial(robot);
  config.registrationParams((fuzz::scratchDir() / "no_config_dir").string());
}
