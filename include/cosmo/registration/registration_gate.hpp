#pragma once
// The validity gate of a registration result: accepts on the registration's own evidence only.
#include <string>

#include "cosmo/registration/registration_params.hpp"

namespace cosmo::registration {

struct RegistrationResult;

/// Sets result.valid and result.reason ("ok" or the first failed criterion).
void applyGate(const RegistrationParams& params, RegistrationResult& result);

}  // namespace cosmo::registration
