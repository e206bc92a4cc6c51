#include "cosmo/common/config_dir.hpp"

namespace cosmo {

std::string defaultConfigDir() {
#ifdef COSMO_SOURCE_DIR
  return std::string(COSMO_SOURCE_DIR) + "/config";
#else
  return "config";
#endif
}

}  // namespace cosmo
