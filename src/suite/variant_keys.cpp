#include "cosmo/suite/variant_keys.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "cosmo/comm/radio_params.hpp"
#include "cosmo/common/nearest_name.hpp"
#include "cosmo/common/param_list.hpp"
#include "cosmo/sequence/gate_threshold.hpp"
#include "cosmo/registration/registration_params.hpp"

namespace cosmo::suite {
namespace {

[[noreturn]] void fail(const VariantValue& v, const std::string& why) { throw std::runtime_error(v.where + ": " + why); }

void requireScalar(const VariantValue& v) {
  if (v.scalar.empty() || !v.fields.empty()) fail(v, "expected a single value");
}

unsigned long long nonNegative(const VariantValue& v) {
  requireScalar(v);
  std::size_t used = 0;
  unsigned long long n = 0;
  try {
    if (v.scalar[0] == '-') throw std::invalid_argument("negative");
    n = std::stoull(v.scalar, &used);
  } catch (const std::exception&) { fail(v, "expected a whole number >= 0, got '" + v.scalar + "'"); }
  if (used != v.scalar.size()) fail(v, "expected a whole number >= 0, got '" + v.scalar + "'");
  return n;
}

/// A YAML node {sub: value} checked by a module's own reader (its keys, types and ranges).
ConfigNode oneKeyNode(const std::string& sub, const VariantValue& v, const std::string& section) {
  requireScalar(v);
  ConfigNode node;
  node.node[sub] = YAML::Load(v.scalar);
  const std::string file = v.where.substr(0, v.where.find(": ") + 2);
  node.where = file + "variants." + section;
  return node;
}

const std::map<std::string, std::map<std::string, std::string>>& registrationPresets() {
  static const std::map<std::string, std::map<std::string, std::string>> presets{
      {"paper", {{"refine", "false"}, {"gate", "paper"}}},  // KISS-Matcher alone, its own checks (the paper)
      {"strict", {{"refine", "true"}, {"gate", "strict"}}},  // config/registration.yaml's own setting
  };
  return presets;
}

VariantKey seedKey() {
  return {"seed", "cosmo_generate --seed N (the sequence's seed replaced)",
          [](const std::string&, const VariantValue& v) { nonNegative(v); },
          [](const std::string&, const VariantValue& v) { return "s" + v.scalar; },
          [](const std::string&, const VariantValue& v, VariantEffect& e) { e.seed = nonNegative(v); }};
}

VariantKey repeatsKey() {  // expanded by the plan into values 0..N-1 (plan.cpp)
  return {"repeats", "N runs with the seeds <sequence seed> + 0 .. N-1",
          [](const std::string&, const VariantValue& v) {
            if (nonNegative(v) > 1000) fail(v, "expected at most 1000 repeats");
          },
          [](const std::string&, const VariantValue& v) { return "r" + v.scalar; },
          [](const std::string&, const VariantValue& v, VariantEffect& e) { e.seed_offset = nonNegative(v); }};
}

VariantKey odometryKey() {
  return {"odometry", "loam (the front-end's own) or reference (the reference trajectories)",
          [](const std::string&, const VariantValue& v) {
            requireScalar(v);
            if (v.scalar != "loam" && v.scalar != "reference")
              fail(v, "expected loam or reference, got '" + v.scalar + "'");
          },
          [](const std::string&, const VariantValue& v) { return "odom-" + v.scalar; },
          [](const std::string&, const VariantValue& v, VariantEffect& e) {
            e.request.push_back([odometry = v.scalar](pipeline::GenerateRequest& r) { r.odometry = odometry; });
          }};
}

VariantKey registrationPresetKey() {
  return {"registration", "a registration preset: paper (KISS-Matcher alone) or strict (refined, strict gate)",
          [](const std::string&, const VariantValue& v) {
            requireScalar(v);
            if (!registrationPresets().count(v.scalar))
              fail(v, "expected a preset, paper or strict, got '" + v.scalar + "'");
          },
          [](const std::string&, const VariantValue& v) { return "reg-" + v.scalar; },
          [](const std::string&, const VariantValue& v, VariantEffect& e) {
            for (const auto& [k, value] : registrationPresets().at(v.scalar)) e.registration[k] = value;
          }};
}

VariantKey registrationParamKey() {
  return {"registration.", "one config/registration.yaml key",
          [](const std::string& sub, const VariantValue& v) {
            registration::RegistrationParams::fromConfig(oneKeyNode(sub, v, "registration"));
          },
          [](const std::string& sub, const VariantValue& v) { return sub + "-" + v.scalar; },
          [](const std::string& sub, const VariantValue& v, VariantEffect& e) { e.registration[sub] = v.scalar; }};
}

VariantKey radioParamKey() {
  return {"radio.", "one config/comm/<model>.yaml key, set in every comm model",
          [](const std::string& sub, const VariantValue& v) {
            if (sub == "preset") fail(v, "the preset is the comm model itself: list the models under `comm:`");
            comm::RadioParams::fromConfig(oneKeyNode(sub, v, "radio"));
          },
          [](const std::string& sub, const VariantValue& v) { return sub + "-" + v.scalar; },
          [](const std::string& sub, const VariantValue& v, VariantEffect& e) { e.radio[sub] = v.scalar; }};
}

/// The registration gate's acceptance threshold (sequence/gate_threshold.hpp): `cosmo_generate --gate-threshold X`,
/// which sets `gate: strict`, `min_structure_overlap: X` on top of the sequence's own keys.
VariantKey gateThresholdKey() {
  const auto check = [](const VariantValue& v) {
    requireScalar(v);
    try {
      std::size_t used = 0;
      const double x = std::stod(v.scalar, &used);
      if (used != v.scalar.size()) throw std::invalid_argument("trailing text");
      sequence::gateThresholdKeys(x);
    } catch (const std::exception&) { fail(v, "expected a threshold in [0, 1], got '" + v.scalar + "'"); }
  };
  return {"gate_threshold", "the strict gate's min_structure_overlap, on top of the sequence's keys (sweep 0.40-0.70)",
          [check](const std::string&, const VariantValue& v) { check(v); },
          [](const std::string&, const VariantValue& v) { return "gate-" + v.scalar; },
          [](const std::string&, const VariantValue& v, VariantEffect& e) {
            e.request.push_back([x = std::stod(v.scalar)](pipeline::GenerateRequest& r) { r.gate_threshold = x; });
          }};
}

/// Outliers added to each finished JRL by `cosmo_jrl inject` (the back-end controls, issue 36).
VariantKey injectKey() {
  static const std::vector<std::string> fields{"rate", "kind", "seed", "group_size", "loops", "rate_of"};
  return {"inject", "outliers added to each finished JRL: {rate: R, kind: random|local|group|mixed, seed: N}, or none",
          [](const std::string&, const VariantValue& v) {
            if (v.fields.empty() && v.scalar == "none") return;  // the sweep's baseline: the dataset as made
            if (v.fields.empty()) fail(v, "expected a map {rate: R, kind: K, seed: N} or none");
            for (const auto& [k, value] : v.fields)
              if (std::find(fields.begin(), fields.end(), k) == fields.end()) {
                const std::string near = nearestName(k, fields);
                fail(v, "unknown field '" + k + "'" + (near.empty() ? "" : " (did you mean '" + near + "'?)"));
              }
            if (!v.fields.count("rate") || !v.fields.count("kind")) fail(v, "needs rate and kind");
            double rate = 0.0;
            try {
              rate = std::stod(v.fields.at("rate"));
            } catch (const std::exception&) { rate = -1.0; }
            if (!(rate > 0.0 && rate < 1.0)) fail(v, "rate: expected a share between 0 and 1 (exclusive)");
            const std::string& kind = v.fields.at("kind");
            if (kind != "random" && kind != "local" && kind != "group" && kind != "mixed")
              fail(v, "kind: expected random, local, group or mixed, got '" + kind + "'");
            if (v.fields.count("loops") && v.fields.at("loops") != "intra" && v.fields.at("loops") != "inter" &&
                v.fields.at("loops") != "both")
              fail(v, "loops: expected intra, inter or both");
            if (v.fields.count("rate_of") && v.fields.at("rate_of") != "injected" && v.fields.at("rate_of") != "all")
              fail(v, "rate_of: expected injected or all");
          },
          [](const std::string&, const VariantValue& v) -> std::string {
            if (v.fields.empty()) return "inj-none";
            const auto get = [&](const char* k, const char* d) { return v.fields.count(k) ? v.fields.at(k) : d; };
            std::string tag = "inj-" + v.fields.at("kind") + "-" + v.fields.at("rate") + "-s" + get("seed", "0");
            if (v.fields.count("group_size")) tag += "-g" + v.fields.at("group_size");
            if (v.fields.count("loops")) tag += "-" + v.fields.at("loops");
            if (v.fields.count("rate_of")) tag += "-of-" + v.fields.at("rate_of");
            return tag;
          },
          [](const std::string&, const VariantValue& v, VariantEffect& e) {
            if (v.fields.empty()) return;
            PostStep step{"cosmo_jrl", "inject", {"--rate", v.fields.at("rate"), "--kind", v.fields.at("kind")}, ""};
            step.args.insert(step.args.end(), {"--seed", v.fields.count("seed") ? v.fields.at("seed") : "0"});
            if (v.fields.count("group_size")) step.args.insert(step.args.end(), {"--group-size", v.fields.at("group_size")});
            if (v.fields.count("loops")) step.args.push_back("--" + v.fields.at("loops"));
            if (v.fields.count("rate_of")) step.args.insert(step.args.end(), {"--rate-of", v.fields.at("rate_of")});
            e.post_steps.push_back(step);
          }};
}

}  // namespace

const std::vector<VariantKey>& variantKeys() {
  static const std::vector<VariantKey> keys{seedKey(),           repeatsKey(),           odometryKey(),
                                            registrationPresetKey(), registrationParamKey(), radioParamKey(),
                                            gateThresholdKey(),      injectKey()};
  return keys;
}

std::vector<std::string> variantKeyNames() {
  std::vector<std::string> names;
  for (const auto& k : variantKeys())
    if (k.name.back() != '.') names.push_back(k.name);
  for (const auto& p : paramKeys<registration::RegistrationParams>()) names.push_back("registration." + p);
  for (const auto& p : paramKeys<comm::RadioParams>()) names.push_back("radio." + p);
  names.insert(names.end(), {"radio.timeout_mode", "radio.size_model"});
  return names;
}

const VariantKey* findVariantKey(const std::string& key, std::string& sub) {
  const std::vector<std::string> names = variantKeyNames();
  if (std::find(names.begin(), names.end(), key) == names.end()) return nullptr;
  for (const auto& k : variantKeys()) {
    if (k.name.back() == '.' && key.rfind(k.name, 0) == 0) {
      sub = key.substr(k.name.size());
      return &k;
    }
    if (k.name == key) {
      sub.clear();
      return &k;
    }
  }
  return nullptr;
}

std::string nameSafe(const std::string& text) {
  std::string out;
  for (const char c : text)
    out += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_' ? c : '-';
  return out;
}

}  // namespace cosmo::suite
