// The only translation unit that includes OpenVDB (its headers are heavy).
#include "sheetgen/env/distance_field.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <cstdint>
#include <mutex>

#include "sheetgen/core/cancelled.hpp"
#include "sheetgen/core/geometry.hpp"

namespace sheetgen {

namespace {

// Feeds our double-precision world mesh to meshToVolume in index space.
struct MeshAdapter {
  const TriangleMesh* mesh;
  double inv_voxel;
  size_t polygonCount() const { return mesh->triangles.size(); }
  size_t pointCount() const { return mesh->vertices.size(); }
  size_t vertexCount(size_t) const { return 3; }
  void getIndexSpacePoint(size_t n, size_t v, openvdb::Vec3d& pos) const {
    const Vec3& p = mesh->vertices[mesh->triangles[n][v]];
    pos = openvdb::Vec3d(p.x() * inv_voxel, p.y() * inv_voxel, p.z() * inv_voxel);
  }
};

// OpenVDB's interrupter protocol, reading the caller's cancel flag.
struct CancelInterrupter {
  const std::atomic<bool>* flag = nullptr;
  void start(const char* = nullptr) {}
  void end() {}
  bool wasInterrupted(int = -1) const { return flag && flag->load(std::memory_order_relaxed); }
};

void initialize_openvdb_once() {
  static std::once_flag flag;
  std::call_once(flag, [] { openvdb::initialize(); });
}

}  // namespace

struct DistanceField::Impl {
  TriangleMesh mesh;
  BoundingBox bounds;
  DistanceFieldOptions options;
  double h = 0, inv_h = 0, band = 0, refine_below = 0;
  openvdb::FloatGrid::Ptr dist;
  openvdb::Int32Grid::Ptr index;
  DistanceFieldStats stats;
  // Flat open-addressing table from leaf origin to the raw value arrays of the
  // distance and index leaves: one probe instead of a four-level tree descent
  // per query (the descent's cache misses dominated the query time).
  struct LeafSlot {
    std::uint64_t key = kEmpty;
    const float* dist = nullptr;
    const openvdb::Int32* index = nullptr;
  };
  static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
  std::vector<LeafSlot> leaf_table;
  std::uint64_t leaf_mask = 0;

  static std::uint64_t leaf_key(const openvdb::Coord& c) {
    // 21 bits per axis of the leaf coordinate (c >> 3): +-2^20 leaves = +-8.4e6 voxels.
    const auto pack = [](int v) { return static_cast<std::uint64_t>((v >> 3) + (1 << 20)) & 0x1FFFFF; };
    return pack(c.x()) | (pack(c.y()) << 21) | (pack(c.z()) << 42);
  }
  static std::uint64_t hash(std::uint64_t k) {
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdULL;
    k ^= k >> 33;
    return k;
  }
  void build_leaf_table() {
    const size_t n = dist->tree().leafCount();
    size_t cap = 16;
    while (cap < 2 * n) cap <<= 1;
    leaf_table.assign(cap, LeafSlot{});
    leaf_mask = cap - 1;
    auto iacc = index->getConstAccessor();
    for (auto it = dist->tree().cbeginLeaf(); it; ++it) {
      const openvdb::Coord origin = it->origin();
      LeafSlot slot;
      slot.key = leaf_key(origin);
      slot.dist = it->buffer().data();
      const auto* ileaf = index->tree().probeConstLeaf(origin);
      slot.index = ileaf ? ileaf->buffer().data() : nullptr;
      for (std::uint64_t h = hash(slot.key) & leaf_mask;; h = (h + 1) & leaf_mask)
        if (leaf_table[h].key == kEmpty) {
          leaf_table[h] = slot;
          break;
        }
    }
  }
  const LeafSlot* find_leaf(const openvdb::Coord& c) const {
    if (leaf_table.empty()) return nullptr;
    const std::uint64_t key = leaf_key(c);
    for (std::uint64_t h = hash(key) & leaf_mask;; h = (h + 1) & leaf_mask) {
      if (leaf_table[h].key == key) return &leaf_table[h];
      if (leaf_table[h].key == kEmpty) return nullptr;
    }
  }

  // Faces around each vertex (CSR), for the closest-point descent.
  std::vector<int> vertex_face_start, vertex_faces;

  void build_adjacency() {
    vertex_face_start.assign(mesh.vertices.size() + 1, 0);
    for (const auto& t : mesh.triangles)
      for (int v : t) ++vertex_face_start[v + 1];
    for (size_t v = 0; v < mesh.vertices.size(); ++v) vertex_face_start[v + 1] += vertex_face_start[v];
    vertex_faces.resize(vertex_face_start.back());
    std::vector<int> fill(vertex_face_start.begin(), vertex_face_start.end() - 1);
    for (int f = 0; f < static_cast<int>(mesh.triangles.size()); ++f)
      for (int v : mesh.triangles[f]) vertex_faces[fill[v]++] = f;
  }

  // The grid's candidate may be a near-closest neighbour of the true closest
  // face (same distance to second order, different closest point). Walk to
  // vertex-adjacent faces while that gets closer.
  ClosestPoint descend(ClosestPoint best, const Vec3& p) const {
    for (int step = 0; step < 64; ++step) {
      const int from = best.face;
      for (int v : mesh.triangles[from])
        for (int k = vertex_face_start[v]; k < vertex_face_start[v + 1]; ++k) {
          const int f = vertex_faces[k];
          const auto& t = mesh.triangles[f];
          const Vec3 q = closest_point_on_triangle(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
          const double d = (q - p).norm();
          if (d < best.distance - 1e-15) {
            best.distance = d;
            best.point = q;
            best.face = f;
          }
        }
      if (best.face == from) break;
    }
    return best;
  }

  ClosestPoint exact_over(const int* faces, int n, const Vec3& p) const {
    ClosestPoint best;
    best.distance = std::numeric_limits<double>::infinity();
    for (int k = 0; k < n; ++k) {
      const auto& t = mesh.triangles[faces[k]];
      const Vec3 q = closest_point_on_triangle(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
      const double d = (q - p).norm();
      if (d < best.distance) {
        best.distance = d;
        best.point = q;
        best.face = faces[k];
      }
    }
    best.exact = n > 0;
    return best;
  }

  ClosestPoint brute_force(const Vec3& p) const {
    ClosestPoint best;
    best.distance = std::numeric_limits<double>::infinity();
    for (int f = 0; f < static_cast<int>(mesh.triangles.size()); ++f) {
      const auto& t = mesh.triangles[f];
      const Vec3 q = closest_point_on_triangle(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
      const double d = (q - p).norm();
      if (d < best.distance) {
        best.distance = d;
        best.point = q;
        best.face = f;
      }
    }
    best.exact = true;
    return best;
  }

  ClosestPoint query(const Vec3& p, bool want_point) const {
    ClosestPoint out;
    if (mesh.triangles.empty()) {
      out.distance = std::numeric_limits<double>::infinity();
      return out;
    }
    // Voxel centres sit at integer index coordinates (transform = uniform scale h).
    const double x = p.x() * inv_h, y = p.y() * inv_h, z = p.z() * inv_h;
    // Far outside the grid's index range: no lookup, just the bound.
    constexpr double kIndexLimit = 1.0e9;
    if (!(std::abs(x) < kIndexLimit && std::abs(y) < kIndexLimit && std::abs(z) < kIndexLimit)) {
      out.distance = std::max(band, bounds.distance(p));
      return out;
    }
    const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    const openvdb::Coord base(static_cast<int>(fx), static_cast<int>(fy), static_cast<int>(fz));
    const double tx = x - fx, ty = y - fy, tz = z - fz;
    float v[8];
    // Corner c is base + (c&1, c>>1&1, c>>2&1); a leaf stores x-major, so the
    // offsets are 64, 8 and 1. When the 8 corners lie in one 8^3 leaf (7 times
    // in 8 per axis), one table probe serves them all.
    const bool in_one_leaf = (base.x() & 7) != 7 && (base.y() & 7) != 7 && (base.z() & 7) != 7;
    // Coordinates beyond the table's 21-bit range take the tree path.
    constexpr int kTableLimit = (1 << 23) - 8;
    const bool in_table = std::abs(base.x()) < kTableLimit && std::abs(base.y()) < kTableLimit && std::abs(base.z()) < kTableLimit;
    // Each corner's leaf (nullptr: no leaf, which reads as background, since an
    // unsigned narrow-band grid has no active tiles) and its offset in it,
    // found once for both the distance and the index grid. A cell
    // that straddles leaves (about a third of the queries) probes the table
    // once per corner: a tree accessor there cost more than the rest of the
    // query, because OpenVDB registers every accessor in a locked hash map.
    const LeafSlot* corner_leaf[8];
    openvdb::Index corner_offset[8];
    if (in_table) {
      if (in_one_leaf) {
        const LeafSlot* leaf = find_leaf(base);
        const openvdb::Index offset = openvdb::FloatTree::LeafNodeType::coordToOffset(base);
        for (int c = 0; c < 8; ++c) {
          corner_leaf[c] = leaf;
          corner_offset[c] = offset + (c & 1) * 64 + ((c >> 1) & 1) * 8 + ((c >> 2) & 1);
        }
      } else {
        for (int c = 0; c < 8; ++c) {
          const openvdb::Coord q = base.offsetBy(c & 1, (c >> 1) & 1, (c >> 2) & 1);
          corner_leaf[c] = find_leaf(q);
          corner_offset[c] = openvdb::FloatTree::LeafNodeType::coordToOffset(q);
        }
      }
      for (int c = 0; c < 8; ++c) v[c] = corner_leaf[c] ? corner_leaf[c]->dist[corner_offset[c]] : static_cast<float>(band);
    } else {
      auto acc = dist->getConstUnsafeAccessor();  // unregistered: read-only grid
      for (int c = 0; c < 8; ++c) v[c] = acc.getValue(base.offsetBy(c & 1, (c >> 1) & 1, (c >> 2) & 1));
    }
    // Inactive voxels hold the background (the band width): all 8 there = outside the band.
    const float background = static_cast<float>(band) * (1.0f - 1e-6f);
    bool all_background = true;
    for (int c = 0; c < 8; ++c) all_background = all_background && v[c] >= background;
    if (all_background) {
      if (static_cast<int>(mesh.triangles.size()) <= options.exact_fallback_triangles) return brute_force(p);
      out.distance = std::max(band, bounds.distance(p));
      return out;
    }
    const double c00 = v[0] + (v[1] - v[0]) * tx, c10 = v[2] + (v[3] - v[2]) * tx;
    const double c01 = v[4] + (v[5] - v[4]) * tx, c11 = v[6] + (v[7] - v[6]) * tx;
    const double c0 = c00 + (c10 - c00) * ty, c1 = c01 + (c11 - c01) * ty;
    const double interpolated = c0 + (c1 - c0) * tz;
    out.distance = interpolated;
    // Trilinear interpolation is poor only where the surface (the kink of the
    // unsigned distance) crosses the cell, i.e. when a corner is within about
    // one voxel of it; elsewhere its error is of order h^2/(8 d).
    const float min_corner = *std::min_element(v, v + 8);
    if (min_corner >= refine_below && !want_point) return out;
    // Near the surface: exact distance to the closest triangles of the 8 corners.
    int faces[8];
    int n = 0;
    const int nf = static_cast<int>(mesh.triangles.size());
    auto add_face = [&](int f) {
      if (f >= 0 && f < nf && std::find(faces, faces + n, f) == faces + n) faces[n++] = f;
    };
    if (in_table) {
      for (int c = 0; c < 8; ++c)
        if (corner_leaf[c] && corner_leaf[c]->index) add_face(corner_leaf[c]->index[corner_offset[c]]);
    } else {
      auto iacc = index->getConstUnsafeAccessor();
      for (int c = 0; c < 8; ++c) add_face(iacc.getValue(base.offsetBy(c & 1, (c >> 1) & 1, (c >> 2) & 1)));
    }
    if (n == 0) return out;
    const ClosestPoint best = exact_over(faces, n, p);
    return want_point ? descend(best, p) : best;
  }
};

DistanceField::DistanceField(const TriangleMesh& mesh, const DistanceFieldOptions& options) : impl_(std::make_unique<Impl>()) {
  initialize_openvdb_once();
  const auto start = std::chrono::steady_clock::now();
  Impl& m = *impl_;
  m.mesh = mesh;
  m.bounds = bounding_box(mesh);
  m.options = options;
  m.h = options.voxel_size;
  m.inv_h = 1.0 / m.h;
  const int band_voxels = std::max(options.band_voxels, 2);
  m.band = band_voxels * m.h;
  m.refine_below = options.refine_below > 0 ? options.refine_below : m.h;
  const auto transform = openvdb::math::Transform::createLinearTransform(m.h);
  m.index = openvdb::Int32Grid::create(static_cast<openvdb::Int32>(openvdb::util::INVALID_IDX));
  if (!mesh.triangles.empty()) {
    MeshAdapter adapter{&m.mesh, m.inv_h};
    // Unsigned: meshes may be open. No renormalisation: it smooths values near
    // self-intersections, and we want the exact per-voxel distances.
    CancelInterrupter interrupter{options.cancel};
    m.dist = openvdb::tools::meshToVolume<openvdb::FloatGrid>(
        interrupter, adapter, *transform, static_cast<float>(band_voxels), static_cast<float>(band_voxels),
        openvdb::tools::UNSIGNED_DISTANCE_FIELD | openvdb::tools::DISABLE_RENORMALIZATION, m.index.get());
    if (interrupter.wasInterrupted()) throw Cancelled();
  } else {
    m.dist = openvdb::FloatGrid::create(static_cast<float>(m.band));
    m.dist->setTransform(transform);
  }
  m.build_adjacency();
  m.build_leaf_table();
  m.stats.active_voxels = m.dist->activeVoxelCount();
  m.stats.memory_bytes = m.dist->memUsage() + m.index->memUsage() + m.leaf_table.capacity() * sizeof(Impl::LeafSlot);
  m.stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

DistanceField::~DistanceField() = default;

double DistanceField::distance(const Vec3& p) const { return impl_->query(p, false).distance; }

ClosestPoint DistanceField::closest(const Vec3& p) const { return impl_->query(p, true); }

Vec3 DistanceField::gradient(const Vec3& p) const {
  const ClosestPoint c = impl_->query(p, true);
  if (c.face >= 0) {
    const Vec3 d = p - c.point;
    const double len = d.norm();
    if (len > 1e-12) return d / len;
    return impl_->mesh.face_normal(c.face);  // on the surface: the face normal's side is arbitrary
  }
  // A bound only (far away): central differences of the bound, then toward the box.
  const double h = impl_->h;
  Vec3 g;
  for (int k = 0; k < 3; ++k) {
    Vec3 e = Vec3::Zero();
    e[k] = h;
    g[k] = distance(p + e) - distance(p - e);
  }
  if (g.norm() > 0) return g.normalized();
  const Vec3 centre = 0.5 * (impl_->bounds.min + impl_->bounds.max);
  return (p - centre).norm() > 0 ? Vec3((p - centre).normalized()) : Vec3::UnitZ();
}

double DistanceField::voxel_size() const { return impl_->h; }
double DistanceField::band_width() const { return impl_->band; }
const DistanceFieldStats& DistanceField::stats() const { return impl_->stats; }
const TriangleMesh& DistanceField::mesh() const { return impl_->mesh; }

}  // namespace sheetgen
