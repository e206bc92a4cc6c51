#include "cosmo/sim/lidar_model.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace cosmo::sim {

#define COSMO_SIM_LIDAR_FIELDS(X)                                                                                     \
  X(beams)                                                                                                            \
  X(columns)                                                                                                          \
  X(rate_hz)                                                                                                          \
  X(fov_up_deg) X(fov_down_deg) X(min_range) X(max_range) X(range_sigma) X(grazing_cos) X(detection_range) X(dropout) \
      X(intensity_scale) X(foliage_spread) X(clockwise)

LidarModel LidarModel::os1_64() { return LidarModel{}; }

LidarModel LidarModel::os1_128() {
  LidarModel m;
  m.name = "os1_128";
  m.beams = 128;
  m.fov_up_deg = 22.5;
  m.fov_down_deg = -22.5;
  return m;
}

LidarModel LidarModel::os1_32() {
  LidarModel m;
  m.name = "os1_32";
  m.beams = 32;
  m.fov_up_deg = 22.5;
  m.fov_down_deg = -22.5;
  return m;
}

LidarModel LidarModel::byName(const std::string& name) {
  if (name == "os1_64") return os1_64();
  if (name == "os1_128") return os1_128();
  if (name == "os1_32") return os1_32();
  throw std::runtime_error("unknown LiDAR model '" + name + "' (known: os1_64, os1_128, os1_32)");
}

LidarModel LidarModel::fromConfig(const ConfigNode& node) {
  std::string model = "os1_64";
  node.read("model", model);
  LidarModel m;
  try {
    m = byName(model);
  } catch (const std::exception& e) { throw std::runtime_error(node.where + ".model: " + e.what()); }
#define X(f) node.read(#f, m.f);
  COSMO_SIM_LIDAR_FIELDS(X)
#undef X
  node.read("range_sigma_per_m", m.range_sigma_per_m);
  node.read("beam_angle_sigma_deg", m.beam_angle_sigma_deg);
  node.read("beam_divergence_mrad", m.beam_divergence_mrad);
  node.read("range_walk", m.range_walk);
  node.read("foliage_mean_free_path", m.foliage_mean_free_path);
  node.read("material_losses", m.material_losses);
  if (m.range_sigma_per_m < 0.0 || m.beam_angle_sigma_deg < 0.0 || m.beam_divergence_mrad < 0.0 || m.range_walk < 0.0 ||
      m.foliage_mean_free_path < 0.0)
    throw std::runtime_error(node.where +
                             ": range_sigma_per_m, beam_angle_sigma_deg, beam_divergence_mrad, range_walk "
                             "and foliage_mean_free_path must be >= 0");
  if (m.beams < 1 || m.columns < 1 || !(m.rate_hz > 0) || !(m.max_range > m.min_range))
    throw std::runtime_error(node.where + ": LiDAR needs beams, columns >= 1, rate_hz > 0, max_range > min_range");
  std::vector<std::string> known{"model",      "range_sigma_per_m",      "beam_angle_sigma_deg", "beam_divergence_mrad",
                                 "range_walk", "foliage_mean_free_path", "material_losses"};
#define X(f) known.emplace_back(#f);
  COSMO_SIM_LIDAR_FIELDS(X)
#undef X
  node.rejectUnknownKeys(known);
  return m;
}

std::string LidarModel::describe() const {
  std::ostringstream os;
  os << std::setprecision(17) << "name=" << name << ';';
#define X(f) os << #f << '=' << f << ';';
  COSMO_SIM_LIDAR_FIELDS(X)
#undef X
  // Only when used: the cache keys of sensors without them stay valid.
  if (range_sigma_per_m > 0.0) os << "range_sigma_per_m=" << range_sigma_per_m << ';';
  if (beam_angle_sigma_deg > 0.0) os << "beam_angle_sigma_deg=" << beam_angle_sigma_deg << ';';
  if (beam_divergence_mrad > 0.0) os << "beam_divergence_mrad=" << beam_divergence_mrad << ';';
  if (range_walk > 0.0) os << "range_walk=" << range_walk << ';';
  if (foliage_mean_free_path > 0.0) os << "foliage_mean_free_path=" << foliage_mean_free_path << ';';
  if (!material_losses) os << "material_losses=0;";
  return os.str();
}

std::vector<double> LidarModel::elevations() const {
  std::vector<double> e(static_cast<std::size_t>(beams));
  const double up = fov_up_deg * M_PI / 180.0, down = fov_down_deg * M_PI / 180.0;
  for (int b = 0; b < beams; ++b) e[b] = beams == 1 ? 0.5 * (up + down) : up + (down - up) * b / (beams - 1);
  return e;
}

double LidarModel::azimuth(int column) const {
  const double frac = static_cast<double>(column) / columns;
  return M_PI + (clockwise ? -1.0 : 1.0) * 2.0 * M_PI * frac;
}

}  // namespace cosmo::sim
