#include "cosmo/jrl/validate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include <Eigen/Cholesky>

#include "cosmo/jrl/io.hpp"

namespace cosmo::jrl {

namespace {

std::string rk(char r) { return std::string(1, r); }
std::string idx(std::size_t i) { return "[" + std::to_string(i) + "]"; }
std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

class Validator {
 public:
  explicit Validator(const Dataset& d) : d_(d) {}

  std::vector<Violation> run() {
    robots();
    for (char r : d_.robots) measurements(r);
    values("groundtruth", d_.groundtruth);
    values("initialization", d_.initialization);
    sharedGroundTruth();
    outliers();
    return std::move(out_);
  }

 private:
  void add(std::string place, std::string problem) { out_.push_back({std::move(place), std::move(problem)}); }

  bool listed(char r) const { return std::find(d_.robots.begin(), d_.robots.end(), r) != d_.robots.end(); }

  void robots() {
    for (std::size_t i = 0; i < d_.robots.size(); ++i) {
      const char r = d_.robots[i];
      if (r < 0x21 || r > 0x7e) add("robots" + idx(i), "robot id is not a printable ASCII character");
      if (std::find(d_.robots.begin(), d_.robots.begin() + static_cast<long>(i), r) !=
          d_.robots.begin() + static_cast<long>(i))
        add("robots" + idx(i), std::string("duplicate robot '") + r + "'");
    }
    auto unlisted = [&](const char* name, const auto& map) {
      for (const auto& kv : map)
        if (!listed(kv.first)) add(std::string(name) + "." + rk(kv.first), "robot is not listed in robots");
    };
    unlisted("measurements", d_.measurements);
    if (d_.groundtruth) unlisted("groundtruth", *d_.groundtruth);
    if (d_.initialization) unlisted("initialization", *d_.initialization);
    if (d_.potential_outliers) unlisted("potential_outlier_factors", *d_.potential_outliers);
    if (d_.outliers) unlisted("outlier_factors", *d_.outliers);
  }

  void unitQuaternion(const Eigen::Quaterniond& q, const std::string& place) {
    const double n = q.norm();
    if (!(std::abs(n - 1.0) <= kUnitNormTolerance)) add(place, "quaternion is not unit (norm " + fmt(n) + ")");
  }

  void finite(const double* v, std::size_t n, const std::string& place) {
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite(v[i])) {
        add(place, "number is not finite");
        return;
      }
  }

  void measured(const Measured& m, const std::string& place) {
    if (const auto* p = std::get_if<Pose3Value>(&m)) {
      finite(p->translation.data(), 3, place + ".translation");
      finite(p->rotation.coeffs().data(), 4, place + ".rotation");
      unitQuaternion(p->rotation, place + ".rotation");
    } else if (const auto* b = std::get_if<BearingRange3>(&m)) {
      const double n =
          std::sqrt(b->bearing.i * b->bearing.i + b->bearing.j * b->bearing.j + b->bearing.k * b->bearing.k);
      if (!(std::abs(n - 1.0) <= kUnitNormTolerance))
        add(place + ".bearing", "Unit3 is not unit (norm " + fmt(n) + ")");
    }
  }

  void covariance(const Factor& f, const std::string& place) {
    const int d = factorDim(f.type);
    const std::size_t n = static_cast<std::size_t>(d * d);
    if (f.covariance.size() != n) {
      add(place, "expected " + std::to_string(n) + " numbers, got " + std::to_string(f.covariance.size()));
      return;
    }
    for (double v : f.covariance)
      if (!std::isfinite(v)) {
        add(place, "covariance holds a non-finite number");
        return;
      }
    const Eigen::MatrixXd S = f.covarianceMatrix();
    const double scale = std::max(1e-300, S.cwiseAbs().maxCoeff());
    const double asym = (S - S.transpose()).cwiseAbs().maxCoeff();
    if (asym > 1e-9 * scale) {
      add(place, "covariance is not symmetric (max |S_ij - S_ji| = " + fmt(asym) + ")");
      return;
    }
    Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (S + S.transpose()));
    if (llt.info() != Eigen::Success || llt.matrixL().toDenseMatrix().diagonal().minCoeff() <= 0.0)
      add(place, "covariance is not positive definite");
  }

  void keyPresent(char r, Key key, const std::string& place, const char* map_name,
                  const std::optional<std::map<char, Values>>& map) {
    if (!map) return;
    const auto it = map->find(r);
    if (it == map->end() || it->second.find(key) == it->second.end())
      add(place, "key " + keyName(key) + " is missing from " + map_name + "." + rk(r));
  }

  static bool isPoseFactor(FactorType t) {
    return t == FactorType::PriorFactorPose3 || t == FactorType::BetweenFactorPose3 ||
           t == FactorType::PriorFactorPose2 || t == FactorType::BetweenFactorPose2;
  }

  void measurements(char r) {
    const auto it = d_.measurements.find(r);
    if (it == d_.measurements.end()) return;
    const std::string pr = "measurements." + rk(r);
    const auto& entries = it->second;
    std::set<std::pair<std::uint64_t, std::uint64_t>> links;  // own Between(Pose) index pairs, sorted
    std::set<std::uint64_t> own;                              // own pose indices referenced
    for (std::size_t e = 0; e < entries.size(); ++e) {
      const std::string pe = pr + idx(e);
      if (e > 0 && entries[e].stamp < entries[e - 1].stamp)
        add(pe + ".stamp", "stamp " + std::to_string(entries[e].stamp) + " is before the previous entry's " +
                               std::to_string(entries[e - 1].stamp));
      for (std::size_t m = 0; m < entries[e].factors.size(); ++m) {
        const Factor& f = entries[e].factors[m];
        const std::string pf = pe + ".measurements" + idx(m);
        const bool prior = isPrior(f.type);
        const std::size_t nkeys = prior ? 1 : 2;
        if (f.keys.size() != nkeys) {
          add(pf, std::string(factorTag(f.type)) + " needs " + std::to_string(nkeys) + " key(s), has " +
                      std::to_string(f.keys.size()));
          continue;
        }
        if (f.measured.index() != measuredKind(f.type))
          add(pf, std::string(factorTag(f.type)) + ": measured value has the wrong type");
        else
          measured(f.measured, pf + (prior ? ".prior" : ".measurement"));
        covariance(f, pf + ".covariance");
        for (std::size_t k = 0; k < nkeys; ++k) {
          const std::string pk = pf + (prior ? ".key" : ".key" + std::to_string(k + 1));
          keyPresent(r, f.keys[k], pk, "groundtruth", d_.groundtruth);
          keyPresent(r, f.keys[k], pk, "initialization", d_.initialization);
        }
        if (!isPoseFactor(f.type)) continue;
        for (Key k : f.keys)
          if (robotOf(k) == r) own.insert(indexOf(k));
        if (!prior && robotOf(f.keys[0]) == r && robotOf(f.keys[1]) == r) {
          const auto a = indexOf(f.keys[0]), b = indexOf(f.keys[1]);
          links.insert({std::min(a, b), std::max(a, b)});
        }
      }
    }
    // Unbroken chain: the first referenced own pose i > 0 is linked to i-1, and every later one to the one before
    // it in index order (indices may skip where a bridge across a front-end's restart joins them). Bounded by the
    // number of referenced poses, whatever the key values.
    std::size_t missing = 0;
    std::optional<std::uint64_t> previous;
    for (std::uint64_t i : own) {
      const std::uint64_t before = previous ? *previous : i - 1;
      previous = i;
      if (i == 0 || links.count({before, i})) continue;
      if (++missing <= 20)
        add(pr,
            "odometry chain broken: no Between factor " + keyName(symbol(r, before)) + " -> " + keyName(symbol(r, i)));
    }
    if (missing > 20) add(pr, "odometry chain broken: " + std::to_string(missing - 20) + " further missing links");
  }

  void values(const char* name, const std::optional<std::map<char, Values>>& map) {
    if (!map) return;
    for (const auto& [r, vals] : *map) {
      std::size_t i = 0;
      for (const auto& [key, v] : vals) {
        const std::string pv = std::string(name) + "." + rk(r) + idx(i++);
        if (const auto* p = std::get_if<Pose3Value>(&v)) {
          finite(p->translation.data(), 3, pv + ".translation");
          finite(p->rotation.coeffs().data(), 4, pv + ".rotation");
          unitQuaternion(p->rotation, pv + ".rotation");
        } else if (const auto* vec = std::get_if<VectorValue>(&v)) {
          finite(vec->data.data(), vec->data.size(), pv + ".data");
        }
      }
    }
  }

  void sharedGroundTruth() {
    if (!d_.groundtruth) return;
    std::map<Key, std::pair<char, const Pose3Value*>> first;
    for (const auto& [r, vals] : *d_.groundtruth) {
      std::size_t i = 0;
      for (const auto& [key, v] : vals) {
        const std::size_t index = i++;
        const auto* p = std::get_if<Pose3Value>(&v);
        if (!p) continue;
        const auto [it, inserted] = first.emplace(key, std::make_pair(r, p));
        if (inserted) continue;
        const Pose3Value& o = *it->second.second;
        const double dt = (p->translation - o.translation).norm();
        const double dq = std::min((p->rotation.coeffs() - o.rotation.coeffs()).norm(),
                                   (p->rotation.coeffs() + o.rotation.coeffs()).norm());
        if (dt > 1e-9 || dq > 1e-9)
          add("groundtruth." + rk(r) + idx(index), "ground truth of " + keyName(key) + " differs from groundtruth." +
                                                       rk(it->second.first) + " (" + fmt(dt) + " m, quaternion " +
                                                       fmt(dq) + ")");
      }
    }
  }

  void outliers() {
    auto inRange = [&](const char* name, const std::map<char, std::set<FactorId>>& map) {
      for (const auto& [r, ids] : map) {
        const auto mit = d_.measurements.find(r);
        std::size_t i = 0;
        for (const FactorId& id : ids) {
          const std::string place = std::string(name) + "." + rk(r) + idx(i++);
          const bool ok = mit != d_.measurements.end() && id.entry < mit->second.size() &&
                          id.measurement < mit->second[id.entry].factors.size();
          if (!ok)
            add(place, "[" + std::to_string(id.entry) + "," + std::to_string(id.measurement) +
                           "] does not name a factor of robot " + rk(r));
        }
      }
    };
    if (d_.potential_outliers) inRange("potential_outlier_factors", *d_.potential_outliers);
    if (!d_.outliers) return;
    inRange("outlier_factors", *d_.outliers);
    for (const auto& [r, ids] : *d_.outliers) {
      const std::set<FactorId>* potential = nullptr;
      if (d_.potential_outliers) {
        const auto it = d_.potential_outliers->find(r);
        if (it != d_.potential_outliers->end()) potential = &it->second;
      }
      std::size_t i = 0;
      for (const FactorId& id : ids) {
        const std::string place = "outlier_factors." + rk(r) + idx(i++);
        if (!potential || !potential->count(id))
          add(place, "[" + std::to_string(id.entry) + "," + std::to_string(id.measurement) +
                         "] is not listed in potential_outlier_factors." + rk(r));
      }
    }
  }

  const Dataset& d_;
  std::vector<Violation> out_;
};

}  // namespace

std::vector<Violation> validate(const Dataset& dataset) { return Validator(dataset).run(); }

}  // namespace cosmo::jrl
