#include "sheetgen/discovery/target.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sheetgen/env/environment.hpp"

namespace sheetgen {

std::vector<double> popularity_factors(const std::vector<int>& counts, double beta) {
  double total = 0;
  for (int c : counts) total += c;
  std::vector<double> out(counts.size());
  for (size_t i = 0; i < counts.size(); ++i) out[i] = std::pow(1.0 - counts[i] / (1.0 + total), beta);
  return out;
}

double edge_rivet_distance(const Environment& env, int ra, const Vec3& a, const Vec3& b, int samples) {
  samples = std::max(2, samples);
  double best = std::numeric_limits<double>::infinity();
  for (int s = 0; s < samples; ++s) {
    const double u = static_cast<double>(s) / (samples - 1);
    best = std::min(best, env.rivet_area_distance(ra, (1 - u) * a + u * b));
  }
  return best;
}

double eq1_likelihood(const std::vector<std::vector<double>>& dist, const std::vector<double>& popularity,
                      const TargetOptions& o) {
  double f = 0;
  for (const auto& row : dist)
    for (size_t i = 0; i < row.size() && i < popularity.size(); ++i)
      f += std::exp(-o.alpha * row[i] / o.scene_unit) * popularity[i];
  return f;
}

double eq1_likelihood(const Part& part, const RealisedPart& realised, const Environment& env,
                      const std::vector<int>& counts, const TargetOptions& o) {
  const std::vector<double> pop = popularity_factors(counts, o.beta);
  const int nra = env.rivet_area_count();
  std::vector<std::vector<double>> dist;
  for (int i = 1; i < part.size(); ++i) {
    const Tab& tab = part.tabs[i];
    if (tab.tag >= 0 || tab.rivet_area >= 0) continue;
    const auto& c = realised.tabs[i].corners;
    for (int e = 1; e <= 3; ++e) {
      std::vector<double> row(nra);
      for (int r = 0; r < nra; ++r) row[r] = edge_rivet_distance(env, r, c[e], c[(e + 1) % 4], o.edge_samples);
      dist.push_back(std::move(row));
    }
  }
  if (dist.empty()) return o.empty_likelihood;
  return eq1_likelihood(dist, pop, o);
}

double eq2_edge_weight(const std::vector<double>& dist, const std::vector<double>& popularity, int times_selected,
                       int steps, const TargetOptions& o) {
  const double se = 1.0 - static_cast<double>(times_selected) / (steps + 1.0);
  double w = 0;
  for (size_t i = 0; i < dist.size() && i < popularity.size(); ++i) {
    const double d = o.alpha * dist[i] / o.scene_unit;
    switch (o.se_reading) {
      case TargetOptions::SeReading::Printed: w += std::exp(-d * se) * popularity[i]; break;
      case TargetOptions::SeReading::Multiply: w += se * std::exp(-d) * popularity[i]; break;
      case TargetOptions::SeReading::Divide: w += std::exp(-d / se) * popularity[i]; break;
      case TargetOptions::SeReading::Plus: w += std::exp(-d * (2.0 - se)) * popularity[i]; break;
    }
  }
  return w;
}

double mh_acceptance(double f_old, double f_new, double q_forward, double q_reverse) {
  if (!(f_new > 0) || !(q_reverse > 0)) return 0.0;
  if (!(f_old > 0) || !(q_forward > 0)) return 1.0;
  return std::min(1.0, (f_new * q_reverse) / (f_old * q_forward));
}

}  // namespace sheetgen
