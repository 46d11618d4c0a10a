#pragma once
// The target of the discovery chains (paper Sec. 4.1): the likelihood of Eq. 1,
// the edge-selection weight of Eq. 2 and the Metropolis-Hastings acceptance
// probability. Distances enter in SearchSettings::scene_unit (0.1 m by default).
// docs/discovery.md derives the acceptance ratio.
#include <vector>

#include "sheetgen/part/part.hpp"
#include "sheetgen/part/realisation.hpp"

namespace sheetgen {

class Environment;

struct TargetOptions {
  double alpha = 1.0;       // Eq. 1-2 distance decay, per scene unit
  double beta = 3.0;        // Eq. 1-2 popularity exponent
  double scene_unit = 0.1;  // m; distances are divided by this before entering exp(-alpha * d)
  int edge_samples = 3;     // points per edge (ends and midpoint) for dist(edge, RA), >= 2
  // Value of Eq. 1 for a part without any feeler tab (the sum is empty); keeps
  // the MH ratio finite when a jump deletes the last feeler.
  double empty_likelihood = 1e-6;
  // How se = 1 - selected / (steps + 1) enters Eq. 2 (docs/discovery.md,
  // docs/ablation_discovery.md). The printed equation has exp(-alpha d se),
  // which makes a frequently chosen edge MORE likely (its distance penalty
  // vanishes), against the paper's prose ("a scaling factor that prefers fewer
  // selected edges"). Readings:
  // Divide:   exp(-alpha d / se)     (default: se scales the exponent, a frequently chosen edge looks farther)
  // Printed:  exp(-alpha d se)       (as printed)
  // Multiply: se * exp(-alpha d)     (se as a plain factor)
  // Plus:     exp(-alpha d (2 - se)) (the fraction with the other sign: 1 + selected / (steps + 1))
  enum class SeReading { Printed, Multiply, Divide, Plus };
  SeReading se_reading = SeReading::Divide;
};

// The popularity factor of Eq. 1-2 per rivet area: (1 - c_i / (1 + sum_j c_j))^beta.
std::vector<double> popularity_factors(const std::vector<int>& connection_counts, double beta);

// Shortest distance (m) from the straight edge a-b to rivet area `ra`, sampled at
// `samples` evenly spaced points (ends included).
double edge_rivet_distance(const Environment& env, int ra, const Vec3& a, const Vec3& b, int samples = 5);

// Eq. 1 from distances: sum_j sum_i exp(-alpha * dist[j][i] / unit) * popularity[i].
// dist: #edges by #rivet areas, m.
double eq1_likelihood(const std::vector<std::vector<double>>& dist, const std::vector<double>& popularity,
                      const TargetOptions& options);
// Eq. 1 on a chain's part: the edges are the free edges (1, 2, 3) of its feeler
// tabs, i.e. non-base tabs with tag < 0 (frozen segment tabs carry their
// segment id >= 0) that are not rivet flanges. Returns
// options.empty_likelihood when there are none.
double eq1_likelihood(const Part& part, const RealisedPart& realised, const Environment& env,
                      const std::vector<int>& connection_counts, const TargetOptions& options);

// Eq. 2 for one free edge from its distances to the rivet areas (m):
// sum_i exp(-alpha * dist[i] / unit / se) * popularity[i], se = 1 - selected / (steps + 1)
// (options.se_reading: Divide; see TargetOptions for the printed and other readings).
double eq2_edge_weight(const std::vector<double>& dist, const std::vector<double>& popularity, int times_selected,
                       int steps, const TargetOptions& options);

// Metropolis-Hastings acceptance probability min(1, f(x') q(x | x') / (f(x) q(x' | x))).
// f_* are target values (Eq. 1), q_* proposal probabilities of the forward and
// reverse moves. A zero forward probability or target returns 1 when f_new > 0 (any move out of
// a zero-probability state is accepted) and 0 when f_new = 0.
double mh_acceptance(double f_old, double f_new, double q_forward, double q_reverse);

}  // namespace sheetgen
