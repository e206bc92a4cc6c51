#pragma once
// The sequence the player replays, resolved (trials::resolveSequence, the one resolution every driver uses) and
// announced: the robots first (/player/robots: the launch starts their front-ends while the trials are read) and
// the resolved sequence's origin at the end (resolved_sequence.hpp). The trials are read here, or, with robot-side
// playback, each on its robot's machine (robot_playback.hpp): the same timing and references either way.
#include "cosmo/trials/sequence_resolution.hpp"

namespace cosmo::ros_glue {

/// Resolves and announces the sequence, its log lines (the pre-flight check, the noise models) in the player's
/// log. Throws std::runtime_error when the check fails (its report logged first).
trials::ResolvedSequence resolvePlayedSequence(const trials::SequenceChoice& choice,
                                               const trials::TrialBases& trial_bases = trials::readTrialBases);

}  // namespace cosmo::ros_glue
