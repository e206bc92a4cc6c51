#pragma once
// One parameter list per module. A params struct names each of its YAML keys once, beside its members:
//
//   template <class Visitor> void visit(Visitor&& v) { v("min_range", min_range); v("max_range", max_range); }
//
// and everything else is derived from that list: the reader (`readParams`), the rejection of keys nobody reads
// (a typo in a config file is an error, not a silently kept default), and the test that checks the struct's
// defaults, the shipped config/*.yaml files and the reader against each other (test_parameter_lists). Keys whose
// value needs its own parsing (enumerations, presets, sub-sections) stay outside the list and are passed as
// `other_keys`.
#include <string>
#include <vector>

#include "cosmo/common/config.hpp"

namespace cosmo {

/// The keys `Params::visit` lists, in its order.
template <class Params>
std::vector<std::string> paramKeys() {
  Params params;
  std::vector<std::string> keys;
  params.visit([&](const char* key, auto&) { keys.emplace_back(key); });
  return keys;
}

/// Overwrites each listed member whose key `node` holds (a missing key keeps the member's value).
template <class Params>
void readListedParams(const ConfigNode& node, Params& params) {
  params.visit([&](const char* key, auto& value) { node.read(key, value); });
}

/// readListedParams, then throws naming the file and key when `node` holds a key that is neither listed nor one
/// of `other_keys`.
template <class Params>
void readParams(const ConfigNode& node, Params& params, std::vector<std::string> other_keys = {}) {
  readListedParams(node, params);
  const std::vector<std::string> listed = paramKeys<Params>();
  other_keys.insert(other_keys.end(), listed.begin(), listed.end());
  node.rejectUnknownKeys(other_keys);
}

}  // namespace cosmo
