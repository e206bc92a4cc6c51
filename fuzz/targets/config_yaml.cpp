// The config files (config/*.yaml, config/comm, config/noise_models, config/sim): the YAML read by ConfigNode and
// handed to every reader of a config section (odometry, place recognition, registration, front-end, radio,
// noise models, simulation). Each reader rejects what is not its own; the others still read the same document.
#include "../fuzz_target.hpp"
#include "../input_file.hpp"
#include "cosmo/comm/radio_params.hpp"
#include "cosmo/common/config.hpp"
#include "cosmo/dataset/noise_models.hpp"
#include "cosmo/odometry/loam_params.hpp"
#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/place_recognition/place_recognizer.hpp"
#include "cosmo/registration/registration_params.hpp"
#include "cosmo/sim/simulation_params.hpp"

using namespace cosmo;

namespace {
template <typename Read>
void tryRead(Read read) {
  try {
    read();
  } catch (const std::runtime_error&) {  // this reader's refusal; the next one reads the same document
  }
}
}  // namespace

COSMO_FUZZ_TARGET(config_yaml) {
  const ConfigNode node = ConfigNode::load(fuzz::inputFile(data, size, "config.yaml"));
  tryRead([&] { odometry::LoamParams::fromConfig(node); });
  tryRead([&] { place_recognition::PlaceRecognitionParams::fromConfig(node); });
  tryRead([&] { registration::RegistrationParams::fromConfig(node); });
  tryRead([&] { frontend::FrontendParams::fromConfig(node); });
  tryRead([&] { comm::RadioParams::fromConfig(node); });
  tryRead([&] { dataset::NoiseModels::fromConfig(node); });
  tryRead([&] { sim::SimulationParams::fromConfig(node); });
}
