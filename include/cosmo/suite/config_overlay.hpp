#pragma once
// The config folder of a group whose variants set config keys (registration.KEY, radio.KEY): a copy of the
// plan's config folder with those keys set in registration.yaml and in each comm model's comm/<model>.yaml, at a
// path fixed by the keys (.suite/config/<hash>/, the job's --config-dir), made once and atomically.
#include "cosmo/suite/plan.hpp"

namespace cosmo::suite {

/// Makes the job's config copy when it needs one and it does not exist yet. Throws std::runtime_error naming
/// the file it cannot write.
void makeConfigOverlay(const Plan& plan, const Job& job);

}  // namespace cosmo::suite
