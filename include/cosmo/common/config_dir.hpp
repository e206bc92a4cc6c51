#pragma once
// The package's config folder in the source tree (compiled in), for the tools and nodes run from a build tree.
#include <string>

namespace cosmo {

std::string defaultConfigDir();

}  // namespace cosmo
