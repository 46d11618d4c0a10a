#include "sheetgen/compose/analysis_cache.hpp"

#include <optional>
#include <string>
#include <type_traits>

#include "sheetgen/compose/candidate.hpp"

namespace sheetgen {

namespace {

// Appends the bytes of a value: doubles compare bit for bit (a -0 and a +0
// give two keys, which only costs an analysis).
template <class T>
void append(std::string& key, const T& v) {
  static_assert(std::is_trivially_copyable<T>::value, "raw bytes only");
  key.append(reinterpret_cast<const char*>(&v), sizeof v);
}

void append(std::string& key, const Vec3& v) {
  for (int i = 0; i < 3; ++i) append(key, v[i]);
}

void append(std::string& key, const std::optional<double>& v) {
  append(key, v.has_value());
  append(key, v.value_or(0.0));
}

void append(std::string& key, const std::string& text) {
  append(key, text.size());
  key.append(text);
}

// The material and the requirements (the FEM's limits and floors).
void append_checks(std::string& key, const Problem& problem) {
  const Material& m = problem.material;
  for (double v : {m.youngs_modulus, m.poisson_ratio, m.density, m.yield_strength, m.ultimate_strength, m.thickness})
    append(key, v);
  const Requirements& r = problem.requirements;
  append(key, r.max_compliance);
  append(key, r.max_deflection);
  append(key, r.min_frequency_hz);
  for (double v : {r.min_margin_of_safety, r.safety_factor, r.min_buckling_factor, r.buckling_model_reserve,
                   r.frequency_model_reserve})
    append(key, v);
  append(key, r.eigen_checks);
}

// The load the part carries: its box, force, mass and every case (names
// included: they are in the FEM's sentences and the result's cases).
void append_load(std::string& key, const Load& load) {
  append(key, load.name);
  for (const Vec3& v : {load.center, load.size, load.force, load.moment, load.center_of_mass}) append(key, v);
  for (double v : {load.rotation.w(), load.rotation.x(), load.rotation.y(), load.rotation.z()}) append(key, v);
  append(key, load.mass);
  for (int i = 0; i < 9; ++i) append(key, load.inertia.data()[i]);
  append(key, load.cases.size());
  for (const LoadCase& c : load.cases) {
    append(key, c.name);
    append(key, c.force);
    append(key, c.moment);
    append(key, c.max_deflection);
  }
}

void append_part(std::string& key, const Part& part) {
  append(key, part.load);
  append(key, part.base.origin);
  append(key, part.base.x_axis);
  append(key, part.base.y_axis);
  append(key, part.base.outline.size());
  for (const Vec2& q : part.base.outline) {
    append(key, q.x());
    append(key, q.y());
  }
  append(key, part.tabs.size());
  for (const Tab& t : part.tabs) {
    append(key, t.parent);
    append(key, t.parent_edge);
    const TabParameters& p = t.params;
    for (double v : {p.d, p.w, p.l, p.theta1, p.theta2, p.theta3}) append(key, v);
    append(key, t.rivet_area);
    append(key, t.riveted_to);
  }
}

}  // namespace

std::string AnalysisCache::key(const Problem& problem, int load_index, const Candidate& c, double element_size) {
  std::string key;
  key.reserve(1024);
  append(key, load_index);
  if (load_index >= 0 && load_index < static_cast<int>(problem.loads.size())) append_load(key, problem.loads[load_index]);
  append(key, element_size);
  append_checks(key, problem);
  const Manufacturing& mf = problem.manufacturing;
  for (double v : {mf.bend_radius, mf.rivet_diameter, mf.rivet_edge_distance, mf.rivet_pitch}) append(key, v);
  append_part(key, c.part);
  append(key, c.self_rivets.size());
  for (const SelfRivetTie& tie : c.self_rivets) {
    append(key, tie.polygon_a);
    append(key, tie.polygon_b);
    append(key, tie.point_a);
    append(key, tie.point_b);
  }
  return key;
}

std::optional<AnalysisCache::Analysis> AnalysisCache::find(const std::string& key) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = analyses_.find(key);
  if (it == analyses_.end()) return std::nullopt;
  ++hits_;
  return it->second;
}

void AnalysisCache::insert(const std::string& key, const Analysis& analysis) {
  std::lock_guard<std::mutex> lock(mutex_);
  analyses_.emplace(key, analysis);
}

int AnalysisCache::hits() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return hits_;
}

std::size_t AnalysisCache::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return analyses_.size();
}

}  // namespace sheetgen
