#include "cosmo/common/text_list.hpp"

#include <sstream>

namespace cosmo {

std::vector<std::string> splitList(const std::string& text, char separator) {
  std::vector<std::string> items;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, separator))
    if (!item.empty()) items.push_back(item);
  return items;
}

}  // namespace cosmo
