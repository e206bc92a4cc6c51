#pragma once
// The likely intended name of a misspelt key or label, for messages ("did you mean 'seed'?").
#include <string>
#include <vector>

namespace cosmo {

/// The name in `known` nearest to `key` by edit distance, when it is close enough to be a likely misspelling
/// (at most max(2, a third of the key's length) edits); "" otherwise.
std::string nearestName(const std::string& key, const std::vector<std::string>& known);

}  // namespace cosmo
