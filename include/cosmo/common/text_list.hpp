#pragma once
// A list given as one piece of text, as command-line options take them ("wifi,proradio"): the items between the
// separators, empty ones left out.
#include <string>
#include <vector>

namespace cosmo {

std::vector<std::string> splitList(const std::string& text, char separator = ',');

}  // namespace cosmo
