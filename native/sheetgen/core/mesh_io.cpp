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

bool host_is_little_endian() {
  const uint16_t probe = 1;
  unsigned char first_byte;
  std::memcpy(&first_byte, &probe, 1);
  return first_byte == 1;
}

// The header's lines; a CRLF file's '\r' is dropped.
class HeaderLines {
 public:
  explicit HeaderLines(const std::string& bytes) : bytes_(bytes) {}
  bool next(std::string& out) {
    if (pos_ >= bytes_.size()) return false;
    size_t nl = bytes_.find('\n', pos_);
    if (nl == std::string::npos) nl = bytes_.size();
    out = bytes_.substr(pos_, nl - pos_);
    if (!out.empty() && out.back() == '\r') out.pop_back();
    pos_ = nl + 1;
    return true;
  }
  size_t pos() const { return pos_; }  // byte offset of the next line

 private:
  const std::string& bytes_;
  size_t pos_ = 0;
};

struct PlyHeader {
  std::string format;
  std::vector<PlyElement> elements;
  size_t body = 0;  // byte offset of the data; one past the end when "end_header" is the last line without a newline
};

// The rest of an "element <name> <count>" line.
PlyElement parse_element_line(std::istringstream& ls, const std::string& name, size_t line_no) {
  PlyElement e;
  long long count = -1;
  std::string count_tok;
  if (!(ls >> e.name >> count_tok) || !parse_long(count_tok, count) || count < 0)
    throw InputError(name, line_field(line_no), "bad element declaration");
  e.count = static_cast<size_t>(count);
  return e;
}

// The rest of a "property <type> <name>" or "property list <count type> <type> <name>" line.
PlyProperty parse_property_line(std::istringstream& ls, const std::string& name, size_t line_no) {
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
  return p;
}

// Header: lines up to "end_header".
PlyHeader parse_ply_header(const std::string& bytes, const std::string& name) {
  HeaderLines lines(bytes);
  std::string line;
  size_t line_no = 1;
  if (!lines.next(line) || line != "ply") throw InputError(name, "line 1", "not a PLY file (first line must be 'ply')");
  PlyHeader h;
  while (lines.next(line)) {
    ++line_no;
    std::istringstream ls(line);
    std::string tag;
    if (!(ls >> tag) || tag == "comment" || tag == "obj_info") continue;
    if (tag == "format") {
      ls >> h.format;
    } else if (tag == "element") {
      h.elements.push_back(parse_element_line(ls, name, line_no));
    } else if (tag == "property") {
      if (h.elements.empty()) throw InputError(name, line_field(line_no), "property before any element");
      h.elements.back().properties.push_back(parse_property_line(ls, name, line_no));
    } else if (tag == "end_header") {
      h.body = lines.pos();
      return h;
    } else {
      throw InputError(name, line_field(line_no), "unexpected header line '" + tag + "'");
    }
  }
  throw InputError(name, "header", "no end_header (truncated PLY)");
}

// Guards against absurd counts before allocating (a hostile header).
void check_declared_counts(const PlyHeader& h, const std::string& bytes, bool ascii, const std::string& name) {
  for (const auto& e : h.elements) {
    size_t min_bytes = 0;
    for (const auto& p : e.properties) min_bytes += p.is_list ? ply_size(p.count_type) : (ascii ? 1 : ply_size(p.type));
    if (min_bytes > 0 && e.count > (bytes.size() - std::min(h.body, bytes.size())) / min_bytes + 1)
      throw InputError(name, "element " + e.name, "declares " + std::to_string(e.count) + " entries but the file is too short (truncated PLY)");
  }
}

// The body's values in file order, from ASCII tokens or binary.
class PlyValues {
 public:
  PlyValues(const std::string& bytes, size_t body, bool ascii, bool swap, const std::string& name)
      : ascii_(ascii),
        ascii_in_(ascii ? bytes.substr(std::min(body, bytes.size())) : std::string()),
        cursor_(bytes, body, swap, name),
        name_(name) {}

  double read(PlyType t, const std::string& where) {
    if (!ascii_) return cursor_.read(t, where);
    std::string tok;
    double v;
    if (!(ascii_in_ >> tok)) throw InputError(name_, where, "file ends early (truncated PLY)");
    if (!parse_double(tok, v)) throw InputError(name_, where, "'" + tok + "' is not a number");
    return v;
  }

 private:
  bool ascii_;
  std::istringstream ascii_in_;
  BinaryCursor cursor_;
  const std::string& name_;
};

struct XyzColumns {
  int x = -1, y = -1, z = -1;  // property indices, -1 when absent
};

XyzColumns xyz_columns(const PlyElement& e) {
  XyzColumns c;
  for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
    if (e.properties[k].name == "x") c.x = k;
    if (e.properties[k].name == "y") c.y = k;
    if (e.properties[k].name == "z") c.z = k;
  }
  return c;
}

bool is_face_vertex_list(const PlyElement& e, const PlyProperty& prop) {
  return e.name == "face" && (prop.name == "vertex_indices" || prop.name == "vertex_index");
}

// Checked before the cast: a uint 4e9, a float 1e30 or NaN would not fit an int.
int vertex_index(double idx, const std::string& where, const std::string& name) {
  if (!(idx >= 0 && idx <= std::numeric_limits<int>::max() && idx == std::floor(idx))) {
    std::ostringstream v;
    v.precision(17);
    v << idx;
    throw InputError(name, where, "vertex index " + v.str() + " is not a valid index");
  }
  return static_cast<int>(idx);
}

// One list property of one entry; a face's vertex list becomes a fan of triangles.
void read_list(PlyValues& in, const PlyElement& e, const PlyProperty& prop, const std::string& where, TriangleMesh& mesh,
               const std::string& name) {
  const bool vertex_list = is_face_vertex_list(e, prop);
  double n = in.read(prop.count_type, where);
  if (!(n >= 0) || n > 1e6) throw InputError(name, where, "bad list length");
  std::vector<int> poly;
  for (int j = 0; j < static_cast<int>(n); ++j) {
    double idx = in.read(prop.type, where);
    if (vertex_list) poly.push_back(vertex_index(idx, where, name));
  }
  if (vertex_list) {
    if (poly.size() < 3) throw InputError(name, where, "face has fewer than 3 vertices");
    for (size_t j = 1; j + 1 < poly.size(); ++j) mesh.triangles.push_back({poly[0], poly[j], poly[j + 1]});
  }
}

void read_element(PlyValues& in, const PlyElement& e, TriangleMesh& mesh, const std::string& name) {
  const bool is_vertex = e.name == "vertex";
  const XyzColumns c = xyz_columns(e);
  if (is_vertex && (c.x < 0 || c.y < 0 || c.z < 0)) throw InputError(name, "element vertex", "needs x, y and z properties");
  // An element without properties occupies no bytes: nothing to read, and
  // looping over a declared count of 2^62 such entries would hang.
  if (e.properties.empty()) return;
  if (is_vertex) mesh.vertices.reserve(e.count);
  for (size_t i = 0; i < e.count; ++i) {
    const std::string where = e.name + " " + std::to_string(i);
    Vec3 p = Vec3::Zero();
    for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
      const auto& prop = e.properties[k];
      if (prop.is_list) {
        read_list(in, e, prop, where, mesh, name);
      } else {
        double v = in.read(prop.type, where);
        if (k == c.x) p.x() = v;
        if (k == c.y) p.y() = v;
        if (k == c.z) p.z() = v;
      }
    }
    if (is_vertex) {
      if (!p.allFinite()) throw InputError(name, where, "vertex coordinate is not finite");
      mesh.vertices.push_back(p);
    }
  }
}

}  // namespace

TriangleMesh parse_ply(const std::string& bytes, const std::string& name) {
  const PlyHeader header = parse_ply_header(bytes, name);
  const bool ascii = header.format == "ascii";
  const bool little = header.format == "binary_little_endian", big = header.format == "binary_big_endian";
  if (!ascii && !little && !big) throw InputError(name, "header", "unknown PLY format '" + header.format + "'");
  check_declared_counts(header, bytes, ascii, name);
  const bool host_little = host_is_little_endian();
  PlyValues in(bytes, header.body, ascii, (big && host_little) || (little && !host_little), name);
  TriangleMesh mesh;
  for (const auto& e : header.elements) read_element(in, e, mesh, name);
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
