#include "cosmo/suite/config_overlay.hpp"

#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace cosmo::suite {
namespace {

/// `file` (its keys under `section:` or at the root) with `keys` set under `section:`.
void setKeys(const fs::path& file, const std::string& section, const std::map<std::string, std::string>& keys,
             const std::string& preset) {
  YAML::Node root = fs::exists(file) ? YAML::LoadFile(file.string()) : YAML::Node(YAML::NodeType::Map);
  YAML::Node node = root[section] ? root[section] : root;
  if (!preset.empty() && !node["preset"]) node["preset"] = preset;
  for (const auto& [k, v] : keys) node[k] = YAML::Load(v);
  std::ofstream out(file, std::ios::trunc);
  out << "# written by cosmo_suite: " << file.filename().string() << " of the suite's config folder with its "
      << "variant's keys set\n"
      << root << "\n";
  if (!out) throw std::runtime_error(file.string() + ": cannot write the config copy");
}

}  // namespace

void makeConfigOverlay(const Plan& plan, const Job& job) {
  if (job.registration.empty() && job.radio.empty()) return;
  const fs::path dir = job.request.config_dir;
  if (dir.empty() || fs::exists(dir / "COMPLETE")) return;
  const fs::path tmp = dir.string() + ".tmp." + std::to_string(::getpid());
  fs::remove_all(tmp);
  fs::create_directories(tmp.parent_path());
  fs::copy(plan.config_dir, tmp, fs::copy_options::recursive);
  if (!job.registration.empty()) setKeys(tmp / "registration.yaml", "registration", job.registration, "");
  if (!job.radio.empty())
    for (const auto& c : job.comms) setKeys(tmp / "comm" / (c + ".yaml"), "comm", job.radio, c);
  std::ofstream(tmp / "COMPLETE") << "\n";
  std::error_code ec;
  fs::rename(tmp, dir, ec);  // another job made the same copy meanwhile: keep it
  if (ec) fs::remove_all(tmp);
}

}  // namespace cosmo::suite
