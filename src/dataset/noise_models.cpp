#include "cosmo/dataset/noise_models.hpp"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <Eigen/Cholesky>

#include "cosmo/dataset/atomic_file.hpp"

namespace cosmo::dataset {
namespace {

Matrix6 fromRowMajor(const double (&v)[36]) {
  Matrix6 m;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) m(r, c) = v[6 * r + c];
  return m;
}

double readNumber(const YAML::Node& n, const std::string& at) {
  if (!n.IsScalar()) throw std::runtime_error(at + ": expected a number");
  try {
    return n.as<double>();
  } catch (const YAML::Exception&) { throw std::runtime_error(at + ": cannot read '" + n.Scalar() + "' as a number"); }
}

std::vector<double> readNumbers(const YAML::Node& n, const std::string& at) {
  if (!n.IsSequence()) throw std::runtime_error(at + ": expected a list");
  std::vector<double> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string ati = at + "[" + std::to_string(i) + "]";
    if (n[i].IsSequence()) {
      for (const double v : readNumbers(n[i], ati)) out.push_back(v);
    } else {
      out.push_back(readNumber(n[i], ati));
    }
  }
  return out;
}

// One section ("odometry" / "loop_closure"): covariance (36 numbers, flat or 6x6) or sigmas (6 numbers).
void readModel(const ConfigNode& config, const std::string& section, Matrix6& cov) {
  if (!config.has(section))
    throw std::runtime_error(config.where + section +
                             ": missing (a noise-model file gives both 'odometry' and "
                             "'loop_closure')");
  const ConfigNode s = config[section];
  const std::string at = s.where;
  if (s.has("covariance")) {
    const std::vector<double> v = readNumbers(s.node["covariance"], at + ".covariance");
    if (v.size() != 36)
      throw std::runtime_error(at + ".covariance: expected 36 numbers (6x6, row by row), got " +
                               std::to_string(v.size()));
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) cov(r, c) = v[6 * r + c];
  } else if (s.has("sigmas")) {
    const std::vector<double> v = readNumbers(s.node["sigmas"], at + ".sigmas");
    if (v.size() != 6)
      throw std::runtime_error(at + ".sigmas: expected 6 numbers [rx ry rz tx ty tz], got " + std::to_string(v.size()));
    cov.setZero();
    for (int i = 0; i < 6; ++i) cov(i, i) = v[i] * v[i];
  } else {
    throw std::runtime_error(at + ": expected 'covariance' (36 numbers) or 'sigmas' (6 numbers)");
  }
  checkCovariance(cov, at + ".covariance");
}

std::string shortest(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof(buf), v);
  std::string s(buf, res.ptr);
  if (s.find_first_of(".en") == std::string::npos) s += ".0";  // keep it a float in YAML
  return s;
}

void writeModel(std::ostringstream& out, const std::string& name, const std::string& comment, const Matrix6& cov) {
  out << name << ":  # " << comment << "\n  covariance:  # 6x6 row by row, [rx ry rz tx ty tz] (rad^2, m^2)\n";
  for (int r = 0; r < 6; ++r) {
    out << "    - [";
    for (int c = 0; c < 6; ++c) out << (c ? ", " : "") << shortest(cov(r, c));
    out << "]\n";
  }
}

/// `s` as a double-quoted YAML scalar (newlines dropped).
std::string yamlQuoted(const std::string& s) {
  std::string q = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') q += '\\';
    if (c != '\n') q += c;
  }
  return q + "\"";
}

}  // namespace

// Covariances stored in ../shared/ref/jrl/tuhh_r3_01_night_wifi.jrl (one constant matrix each, jrl.md §10).
Matrix6 NoiseModels::defaultOdometry() {
  static const double v[36] = {
      8.664332784342755e-05,   5.481831610932607e-05,   -7.964219361003885e-06,  3.473659140303042e-05,
      -1.0702875591740687e-05, 7.611892419335785e-05,   5.481831610932607e-05,   0.00016522263380701837,
      -0.00011692669571372204, 0.00022824521540270852,  -0.00013806228333946975, -3.421830670984823e-05,
      -7.964219361003885e-06,  -0.00011692669571372204, 0.0005381079849362374,   -0.000947392969228125,
      0.0005551196475963057,   -3.956172921006819e-05,  3.473659140303042e-05,   0.00022824521540270852,
      -0.000947392969228125,   0.003327966145563148,    -0.0011277082559620541,  4.247413678881742e-06,
      -1.0702875591740687e-05, -0.00013806228333946975, 0.0005551196475963057,   -0.0011277082559620541,
      0.0016571793369998377,   1.602556206416173e-05,   7.611892419335785e-05,   -3.421830670984823e-05,
      -3.956172921006819e-05,  4.247413678881742e-06,   1.602556206416173e-05,   0.0012022888868178793};
  return fromRowMajor(v);
}

Matrix6 NoiseModels::defaultLoopClosure() {
  static const double v[36] = {
      7.261267917207106e-05,   -6.308419093747482e-06,  -6.6480214680723265e-06, -0.00012102009943541364,
      -0.00013703522527208826, -4.296619475214297e-05,  -6.308419093747482e-06,  5.2220067940032775e-05,
      -6.664294575830228e-06,  0.0001864684824069499,   3.205809365660089e-05,   0.00017644646745610177,
      -6.6480214680723265e-06, -6.664294575830228e-06,  3.841673687764327e-05,   -0.00012271523196180075,
      -6.026389868849037e-05,  -0.00011207353583649117, -0.00012102009943541364, 0.0001864684824069499,
      -0.00012271523196180075, 0.004482443857442866,    0.0008090144358994478,   0.00134471915225839,
      -0.00013703522527208826, 3.205809365660089e-05,   -6.026389868849037e-05,  0.0008090144358994478,
      0.002826631942686872,    0.00040090223180635836,  -4.296619475214297e-05,  0.00017644646745610177,
      -0.00011207353583649117, 0.00134471915225839,     0.00040090223180635836,  0.006550513096585429};
  return fromRowMajor(v);
}

void checkCovariance(const Matrix6& cov, const std::string& what) {
  if (!cov.allFinite()) throw std::runtime_error(what + ": covariance has NaN or Inf entries");
  const double scale = cov.cwiseAbs().maxCoeff();
  if ((cov - cov.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
    throw std::runtime_error(what + ": covariance is not symmetric");
  const Eigen::LLT<Matrix6> llt(cov);
  if (llt.info() != Eigen::Success || scale <= 0.0)
    throw std::runtime_error(what + ": covariance is not positive definite");
}

NoiseModels NoiseModels::fromConfig(const ConfigNode& config) {
  NoiseModels m;
  if (!config.node || !config.node.IsMap())
    throw std::runtime_error(config.where + "expected a map with 'odometry' and 'loop_closure'");
  config.read("environment", m.environment);
  if (config.has("unknown")) {
    std::string why;
    config.read("unknown", why);
    throw NoiseModelsUnknown(
        config.where + "unknown: the noise models of environment '" + m.environment + "' are not known (" + why + ")",
        why);
  }
  config.read("provenance", m.provenance);
  readModel(config, "odometry", m.odometry);
  readModel(config, "loop_closure", m.loop_closure);
  if (config.has("estimated_from")) {
    const ConfigNode e = config["estimated_from"];
    NoiseModelRecord r;
    e.read("trial", r.trial);
    e.read("odometry_factors", r.odometry_factors);
    e.read("loop_closures", r.loop_closures);
    e.read("loop_closures_left_out", r.loop_closures_left_out);
    e.read("max_translation_error", r.max_translation_error);
    e.read("max_rotation_error", r.max_rotation_error);
    m.estimated_from = r;
  }
  return m;
}

NoiseModels NoiseModels::load(const std::string& yaml_path) {
  NoiseModels m = fromConfig(ConfigNode::load(yaml_path));
  m.source = yaml_path;
  return m;
}

std::string NoiseModels::toYaml(const std::string& header_comment) const {
  std::ostringstream out;
  std::istringstream lines(header_comment);
  for (std::string line; std::getline(lines, line);) out << "#" << (line.empty() ? "" : " ") << line << "\n";
  out << "environment: " << yamlQuoted(environment) << "  # informative label\n";
  if (!provenance.empty()) out << "provenance: " << yamlQuoted(provenance) << "\n";
  if (estimated_from) {
    const NoiseModelRecord& r = *estimated_from;
    out << "estimated_from:  # the single-trial run, the measurements used and the good-loop-closure thresholds\n"
        << "  trial: " << yamlQuoted(r.trial) << "\n"
        << "  odometry_factors: " << r.odometry_factors << "\n"
        << "  loop_closures: " << r.loop_closures << "\n"
        << "  loop_closures_left_out: " << r.loop_closures_left_out << "\n"
        << "  max_translation_error: " << shortest(r.max_translation_error) << "  # m\n"
        << "  max_rotation_error: " << shortest(r.max_rotation_error) << "  # rad\n";
  }
  writeModel(out, "odometry", "covariance of every odometry factor <r>(i-1) -> <r>i", odometry);
  writeModel(out, "loop_closure", "covariance of every loop closure, intra- and inter-robot", loop_closure);
  return out.str();
}

std::string NoiseModels::describe() const {
  const NoiseModels& m = *this;
  std::ostringstream out;
  out << (m.source.empty() ? std::string("(built in code)") : m.source) << " (" << m.environment;
  if (!m.provenance.empty()) out << ": " << m.provenance;
  if (m.estimated_from) {
    const NoiseModelRecord& r = *m.estimated_from;
    out << "; estimated from " << r.trial << ": " << r.odometry_factors << " odometry factors, " << r.loop_closures
        << " loop closures (" << r.loop_closures_left_out << " left out over " << r.max_translation_error << " m / "
        << r.max_rotation_error << " rad)";
  }
  out << ")";
  return out.str();
}

void NoiseModels::save(const std::string& yaml_path, const std::string& header_comment) const {
  checkCovariance(odometry, yaml_path + ": odometry");
  checkCovariance(loop_closure, yaml_path + ": loop_closure");
  writeFileAtomically(yaml_path, toYaml(header_comment));
}

}  // namespace cosmo::dataset
