#include "sheetgen/compose/analysis_memo.hpp"

#include <type_traits>
#include <utility>

namespace sheetgen {

namespace {

// Appends the bytes of trivially copyable values: equal keys mean bitwise
// equal inputs, so a hit never stands in for a part that differs in the last bit.
class KeyWriter {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable<T>::value, "only plain values go into a key");
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void put(const Vec3& p) {
    for (int i = 0; i < 3; ++i) put(p[i]);
  }
  template <class T>
  void put_all(const std::vector<T>& values) {
    put(values.size());
    for (const T& v : values) put(v);
  }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

}  // namespace

std::string AnalysisMemo::key_of(const PlateGeometry& geometry, const PartModelOptions& options) {
  KeyWriter w;
  w.put(options.element_size);
  w.put(options.eigen_checks);
  w.put(options.element.alpha_b);
  w.put(options.element.beta0);
  w.put(options.element.transverse_shear);
  w.put(options.element.shear_correction);
  w.put(geometry.polygons.size());
  for (const auto& polygon : geometry.polygons) w.put_all(polygon);
  w.put_all(geometry.rivet_area);
  w.put_all(geometry.rivet_edge);
  w.put_all(geometry.parent);
  w.put_all(geometry.bend_angle);
  w.put(options.self_rivets.size());
  for (const SelfRivetTie& tie : options.self_rivets) {
    w.put(tie.polygon_a);
    w.put(tie.polygon_b);
    w.put(tie.point_a);
    w.put(tie.point_b);
  }
  return w.take();
}

std::optional<MemoEntry> AnalysisMemo::find(const std::string& key) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = entries_.find(key);
  if (it == entries_.end()) {
    ++stats_.misses;
    return std::nullopt;
  }
  ++stats_.hits;
  return it->second;
}

void AnalysisMemo::insert(const std::string& key, MemoEntry entry) {
  std::lock_guard<std::mutex> lock(mutex_);
  entries_.emplace(key, std::move(entry));
}

MemoStats AnalysisMemo::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

}  // namespace sheetgen
