#pragma once
// The keys a suite file's `variants:` section may hold, one registry: each key says how a value is checked, the
// part of the dataset's name it gives, and what it changes in the run (cosmo_generate options, config keys, or a
// step on the finished JRL). Adding a variant is one entry in variant_keys.cpp.
//
//   seed: [1, 2]                       cosmo_generate --seed N                          name part s1, s2
//   repeats: 3                         seeds: the sequence's own + 0, 1, 2              r0, r1, r2
//   odometry: [loam, reference]        --odometry X                                     odom-loam, odom-reference
//   registration: [paper, strict]      config/registration.yaml presets                 reg-paper, reg-strict
//   registration.KEY: [v1, v2]         one config/registration.yaml key                 KEY-v1 (e.g. min_overlap-0.4)
//   radio.KEY: [v1, v2]                one config/comm/<model>.yaml key, every model    KEY-v1 (bandwidth_kBps-500)
//   gate_threshold: [0.45, 0.62]       cosmo_generate --gate-threshold X                gate-0.45
//   inject: [none, {rate: 0.1, kind: random, seed: 1}]   `cosmo_jrl inject` on each JRL   inj-none, inj-random-0.1-s1
//
// Config keys reach the run through a copy of the config folder with those keys set (a sequence's own
// `registration:` keys still go on top of it, so a variant may not set a key its sequence sets: plan.cpp stops).
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cosmo/common/config.hpp"
#include "cosmo/pipeline/generate_request.hpp"

namespace cosmo::suite {

/// A step run on each finished JRL: `<program> <verb> IN OUT <args>`; OUT = IN's stem + `suffix` + ".jrl", which
/// then is the dataset (its stats and figures are made again from it).
struct PostStep {
  std::string program;  ///< a cosmo command beside cosmo_suite, e.g. "cosmo_jrl"
  std::string verb;     ///< e.g. "inject"
  std::vector<std::string> args;
  std::string suffix;  ///< e.g. "_inj-random-0.1-s1"
};

/// What the variants of one dataset group change in its run.
struct VariantEffect {
  std::vector<std::function<void(pipeline::GenerateRequest&)>> request;  ///< what it sets in the run's request
  std::map<std::string, std::string> registration;  ///< config/registration.yaml keys
  std::map<std::string, std::string> radio;         ///< config/comm/<model>.yaml keys (every comm model)
  std::vector<PostStep> post_steps;
  std::optional<unsigned long long> seed;           ///< the seed
  std::optional<unsigned long long> seed_offset;    ///< repeats: the sequence's seed + this
};

/// One value of a variant key: a scalar as written, or a map of scalars (inject).
struct VariantValue {
  std::string scalar;
  std::map<std::string, std::string> fields;
  std::string where;  ///< "<suite file>: variants.<key>[i]", for messages
};

struct VariantKey {
  std::string name;  ///< the suite-file key; "radio." and "registration." entries take any parameter after the dot
  std::string help;
  /// Throws std::runtime_error naming value.where when the value is not valid. `sub`: the text after "name.".
  std::function<void(const std::string& sub, const VariantValue& value)> check;
  /// The value's part of a dataset name (letters, digits, '.', '-', '_').
  std::function<std::string(const std::string& sub, const VariantValue& value)> tag;
  std::function<void(const std::string& sub, const VariantValue& value, VariantEffect& effect)> apply;
};

/// Every variant key.
const std::vector<VariantKey>& variantKeys();

/// Every name a suite file may use under `variants:` ("seed", ..., "radio.bandwidth_kBps", "registration.refine",
/// ...), for the nearest-name message.
std::vector<std::string> variantKeyNames();

/// The entry of `key` and the text after its dot ("radio.d_init" -> the radio entry, "d_init"); nullptr when
/// the registry has no such key.
const VariantKey* findVariantKey(const std::string& key, std::string& sub);

/// Makes a text safe as a part of a file name: letters, digits, '.', '-' and '_' kept, anything else '-'.
std::string nameSafe(const std::string& text);

}  // namespace cosmo::suite
