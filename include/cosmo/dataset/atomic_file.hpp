#pragma once
// Writing a text file so that readers never see a half-written one: write "<path>.tmp.<pid>" in the same
// folder, flush, then rename over `path` (atomic on POSIX file systems).
#include <string>

namespace cosmo::dataset {

/// Throws std::runtime_error naming the path when the folder is missing or the write/rename fails (the
/// temporary file is removed then, and an existing `path` is left untouched).
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace cosmo::dataset
