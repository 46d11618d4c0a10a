#include "sheetgen/core/mesh_io.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "sheetgen/core/input_error.hpp"

namespace sheetgen {

namespace {

// Mesh files are read whole; a cap keeps a huge (or sparse, truncate-made)
// file from exhausting memory. 2 GiB is ~90 M triangles of binary PLY.
constexpr std::uintmax_t kMaxMeshBytes = 2048ull << 20;

std::string read_file(const std::string& path, const std::string& name) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(name, "", "cannot open the mesh file (" + std::string(std::strerror(errno)) + ")");
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(std::filesystem::u8path(path), ec);
  if (!ec && size > kMaxMeshBytes)
    throw InputError(name, "", "is " + std::to_string(size >> 20) + " MiB; mesh files are limited to " +
                                   std::to_string(kMaxMeshBytes >> 20) + " MiB");
  std::string bytes;
  if (!ec) {
    // Read straight into one buffer (a stringstream would hold the file twice).
    bytes.resize(static_cast<size_t>(size));
    in.read(bytes.data(), static_cast<std::streamsize>(size));
    bytes.resize(static_cast<size_t>(in.gcount()));
  } else {
    std::ostringstream ss;
    ss << in.rdbuf();
    bytes = ss.str();
  }
  if (in.bad()) throw InputError(name, "", "cannot read the mesh file");
  return bytes;
}

std::string lower_extension(const std::string& path) {
  auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string line_field(size_t line) { return "line " + std::to_string(line); }

// Parses a double with strtod; rejects partial tokens.
bool parse_double(const std::string& token, double& out) {
  if (token.empty()) return false;
  char* end = nullptr;
  out = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size();
}

bool parse_long(const std::string& token, long long& out) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtoll(token.c_str(), &end, 10);
  return errno == 0 && end == token.c_str() + token.size();
}

}  // namespace

TriangleMesh parse_obj(const std::string& text, const std::string& name) {
  TriangleMesh mesh;
  size_t line_no = 0;
  std::vector<int> poly;
  // Lines are found in place and only "v" and "f" lines are copied: a stream
  // over the text plus getline copies held a 1 GiB one-line file five times.
  auto space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  for (size_t pos = 0; pos < text.size();) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const size_t begin = pos;
    pos = end + 1;
    ++line_no;
    size_t t0 = begin;
    while (t0 < end && space(text[t0])) ++t0;
    size_t t1 = t0;
    while (t1 < end && !space(text[t1])) ++t1;
    const std::string tag = t1 - t0 == 1 ? text.substr(t0, 1) : std::string();
    if (tag != "v" && tag != "f") continue;  // comments, empty lines and records we do not need
    std::istringstream ls(text.substr(t1, end - t1));
    if (tag == "v") {
      Vec3 p;
      for (int k = 0; k < 3; ++k) {
        std::string tok;
        if (!(ls >> tok) || !parse_double(tok, p[k]))
          throw InputError(name, line_field(line_no), "vertex needs three numbers");
        if (!std::isfinite(p[k])) throw InputError(name, line_field(line_no), "vertex coordinate is not finite (" + tok + ")");
      }
      mesh.vertices.push_back(p);
    } else if (tag == "f") {
      poly.clear();
      std::string tok;
      while (ls >> tok) {
        // "i", "i/t", "i//n", "i/t/n": the vertex index is before the first slash.
        long long idx;
        if (!parse_long(tok.substr(0, tok.find('/')), idx) || idx == 0)
          throw InputError(name, line_field(line_no), "face index '" + tok + "' is not a valid OBJ index");
        long long nv = static_cast<long long>(mesh.vertices.size());
        long long zero_based = idx > 0 ? idx - 1 : nv + idx;  // negative = relative to the end
        if (zero_based < 0 || zero_based >= nv)
          throw InputError(name, line_field(line_no), "face index " + std::to_string(idx) + " is out of range (" + std::to_string(nv) + " vertices so far)");
        poly.push_back(static_cast<int>(zero_based));
      }
      if (poly.size() < 3) throw InputError(name, line_field(line_no), "face has fewer than 3 vertices");
      for (size_t k = 1; k + 1 < poly.size(); ++k) mesh.triangles.push_back({poly[0], poly[k], poly[k + 1]});
    }
    // Other records (vn, vt, o, g, s, usemtl, mtllib, l, p) carry nothing we need.
  }
  return mesh;
}

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool ply_type(const std::string& s, PlyType& t) {
  static const std::pair<const char*, PlyType> names[] = {
      {"char", PlyType::Int8},     {"int8", PlyType::Int8},     {"uchar", PlyType::UInt8},   {"uint8", PlyType::UInt8},
      {"short", PlyType::Int16},   {"int16", PlyType::Int16},   {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16},
      {"int", PlyType::Int32},     {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},   {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64}, {"float64", PlyType::Float64}};
  for (const auto& [n, v] : names)
    if (s == n) { t = v; return true; }
  return false;
}

size_t ply_size(PlyType t) {
  switch (t) {
    case PlyType::Int8: case PlyType::UInt8: return 1;
    case PlyType::Int16: case PlyType::UInt16: return 2;
    case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 1;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;
};

struct PlyElement {
  std::string name;
  size_t count = 0;
  std::vector<PlyProperty> properties;
};

// Reads one value of a binary PLY stream; `swap` for big-endian files.
class BinaryCursor {
 public:
  BinaryCursor(const std::string& bytes, size_t pos, bool swap, const std::string& name)
      : bytes_(bytes), pos_(pos), swap_(swap), name_(name) {}
  double read(PlyType t, const std::string& where) {
    size_t n = ply_size(t);
    if (pos_ + n > bytes_.size()) throw InputError(name_, where, "file ends early (truncated binary PLY)");
    unsigned char buf[8];
    std::memcpy(buf, bytes_.data() + pos_, n);
    pos_ += n;
    if (swap_) std::reverse(buf, buf + n);
    switch (t) {
      case PlyType::Int8: { int8_t v; std::memcpy(&v, buf, 1); return v; }
      case PlyType::UInt8: { uint8_t v; std::memcpy(&v, buf, 1); return v; }
      case PlyType::Int16: { int16_t v; std::memcpy(&v, buf, 2); return v; }
      case PlyType::UInt16: { uint16_t v; std::memcpy(&v, buf, 2); return v; }
      case PlyType::Int32: { int32_t v; std::memcpy(&v, buf, 4); return v; }
      case PlyType::UInt32: { uint32_t v; std::memcpy(&v, buf, 4); return v; }
      case PlyType::Float32: { float v; std::memcpy(&v, buf, 4); return v; }
      case PlyType::Float64: { double v; std::memcpy(&v, buf, 8); return v; }
    }
    return 0;
  }
 private:
  const std::string& bytes_;
  size_t pos_;
  bool swap_;
  const std::string& name_;
};

}  // namespace

TriangleMesh parse_ply(const std::string& bytes, const std::string& name) {
  // Header: lines up to "end_header".
  size_t pos = 0;
  auto next_line = [&](std::string& out) -> bool {
    if (pos >= bytes.size()) return false;
    size_t nl = bytes.find('\n', pos);
    if (nl == std::string::npos) nl = bytes.size();
    out = bytes.substr(pos, nl - pos);
    if (!out.empty() && out.back() == '\r') out.pop_back();
    pos = nl + 1;
    return true;
  };
  std::string line;
  size_t line_no = 1;
  if (!next_line(line) || line != "ply") throw InputError(name, "line 1", "not a PLY file (first line must be 'ply')");
  std::string format;
  std::vector<PlyElement> elements;
  bool ended = false;
  while (next_line(line)) {
    ++line_no;
    std::istringstream ls(line);
    std::string tag;
    if (!(ls >> tag) || tag == "comment" || tag == "obj_info") continue;
    if (tag == "format") {
      ls >> format;
    } else if (tag == "element") {
      PlyElement e;
      long long count = -1;
      std::string count_tok;
      if (!(ls >> e.name >> count_tok) || !parse_long(count_tok, count) || count < 0)
        throw InputError(name, line_field(line_no), "bad element declaration");
      e.count = static_cast<size_t>(count);
      elements.push_back(e);
    } else if (tag == "property") {
      if (elements.empty()) throw InputError(name, line_field(line_no), "property before any element");
      PlyProperty p;
      std::string t;
      ls >> t;
      if (t == "list") {
        std::string ct, it;
        if (!(ls >> ct >> it >> p.name) || !ply_type(ct, p.count_type) || !ply_type(it, p.type))
          throw InputError(name, line_field(line_no), "bad list property");
        p.is_list = true;
      } else if (!ply_type(t, p.type) || !(ls >> p.name)) {
        throw InputError(name, line_field(line_no), "unknown property type '" + t + "'");
      }
      elements.back().properties.push_back(p);
    } else if (tag == "end_header") {
      ended = true;
      break;
    } else {
      throw InputError(name, line_field(line_no), "unexpected header line '" + tag + "'");
    }
  }
  if (!ended) throw InputError(name, "header", "no end_header (truncated PLY)");
  const bool ascii = format == "ascii";
  const bool little = format == "binary_little_endian", big = format == "binary_big_endian";
  if (!ascii && !little && !big) throw InputError(name, "header", "unknown PLY format '" + format + "'");

  // Guard against absurd counts before allocating (a hostile header).
  for (const auto& e : elements) {
    size_t min_bytes = 0;
    for (const auto& p : e.properties) min_bytes += p.is_list ? ply_size(p.count_type) : (ascii ? 1 : ply_size(p.type));
    if (min_bytes > 0 && e.count > (bytes.size() - std::min(pos, bytes.size())) / min_bytes + 1)
      throw InputError(name, "element " + e.name, "declares " + std::to_string(e.count) + " entries but the file is too short (truncated PLY)");
  }

  TriangleMesh mesh;
  // pos is one past the end when "end_header" is the last line without a newline.
  std::istringstream ascii_in(ascii ? bytes.substr(std::min(pos, bytes.size())) : std::string());
  const uint16_t probe = 1;
  unsigned char first_byte;
  std::memcpy(&first_byte, &probe, 1);
  const bool host_little = first_byte == 1;
  BinaryCursor cursor(bytes, pos, (big && host_little) || (little && !host_little), name);
  auto read_value = [&](PlyType t, const std::string& where) -> double {
    if (!ascii) return cursor.read(t, where);
    std::string tok;
    double v;
    if (!(ascii_in >> tok)) throw InputError(name, where, "file ends early (truncated PLY)");
    if (!parse_double(tok, v)) throw InputError(name, where, "'" + tok + "' is not a number");
    return v;
  };

  for (const auto& e : elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    int ix = -1, iy = -1, iz = -1;
    for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
      if (e.properties[k].name == "x") ix = k;
      if (e.properties[k].name == "y") iy = k;
      if (e.properties[k].name == "z") iz = k;
    }
    if (is_vertex && (ix < 0 || iy < 0 || iz < 0)) throw InputError(name, "element vertex", "needs x, y and z properties");
    // An element without properties occupies no bytes: nothing to read, and
    // looping over a declared count of 2^62 such entries would hang.
    if (e.properties.empty()) continue;
    if (is_vertex) mesh.vertices.reserve(e.count);
    std::vector<int> poly;
    for (size_t i = 0; i < e.count; ++i) {
      const std::string where = e.name + " " + std::to_string(i);
      Vec3 p = Vec3::Zero();
      for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
        const auto& prop = e.properties[k];
        if (prop.is_list) {
          double n = read_value(prop.count_type, where);
          if (!(n >= 0) || n > 1e6) throw InputError(name, where, "bad list length");
          poly.clear();
          for (int j = 0; j < static_cast<int>(n); ++j) {
            double idx = read_value(prop.type, where);
            if (is_face && (prop.name == "vertex_indices" || prop.name == "vertex_index")) {
              // Checked before the cast: a uint 4e9, a float 1e30 or NaN would not fit an int.
              if (!(idx >= 0 && idx <= std::numeric_limits<int>::max() && idx == std::floor(idx))) {
                std::ostringstream v;
                v.precision(17);
                v << idx;
                throw InputError(name, where, "vertex index " + v.str() + " is not a valid index");
              }
              poly.push_back(static_cast<int>(idx));
            }
          }
          if (is_face && (prop.name == "vertex_indices" || prop.name == "vertex_index")) {
            if (poly.size() < 3) throw InputError(name, where, "face has fewer than 3 vertices");
            for (size_t j = 1; j + 1 < poly.size(); ++j) mesh.triangles.push_back({poly[0], poly[j], poly[j + 1]});
          }
        } else {
          double v = read_value(prop.type, where);
          if (k == ix) p.x() = v;
          if (k == iy) p.y() = v;
          if (k == iz) p.z() = v;
        }
      }
      if (is_vertex) {
        if (!p.allFinite()) throw InputError(name, where, "vertex coordinate is not finite");
        mesh.vertices.push_back(p);
      }
    }
  }
  return mesh;
}

TriangleMesh read_obj(const std::string& path, const std::string& display_name) {
  const std::string name = display_name.empty() ? path : display_name;
  return parse_obj(read_file(path, name), name);
}

TriangleMesh read_ply(const std::string& path, const std::string& display_name) {
  const std::string name = display_name.empty() ? path : display_name;
  return parse_ply(read_file(path, name), name);
}

TriangleMesh read_mesh(const std::string& path, const std::string& display_name) {
  const std::string name = display_name.empty() ? path : display_name;
  const std::string ext = lower_extension(path);
  if (ext == "obj") return read_obj(path, name);
  if (ext == "ply") return read_ply(path, name);
  throw InputError(name, "", "unsupported mesh format '." + ext + "' (use .obj or .ply)");
}

void validate_mesh(const TriangleMesh& mesh, const std::string& file, const std::string& field) {
  if (mesh.vertices.empty() || mesh.triangles.empty())
    throw InputError(file, field, "the mesh is empty (" + std::to_string(mesh.vertices.size()) + " vertices, " +
                                      std::to_string(mesh.triangles.size()) + " triangles)");
  for (size_t i = 0; i < mesh.vertices.size(); ++i)
    if (!mesh.vertices[i].allFinite()) throw InputError(file, field + " vertex " + std::to_string(i), "vertex coordinate is not finite");
  const int nv = static_cast<int>(mesh.vertices.size());
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles[f][k] < 0 || mesh.triangles[f][k] >= nv)
        throw InputError(file, field + " triangle " + std::to_string(f),
                         "vertex index " + std::to_string(mesh.triangles[f][k]) + " is out of range (" + std::to_string(nv) + " vertices)");
}

void write_obj(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  out.precision(17);
  for (const auto& v : mesh.vertices) out << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& t : mesh.triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace sheetgen
