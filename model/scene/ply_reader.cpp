#include "scene/ply_reader.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "scene/ply_header.h"
#include "scene/scene.h"

namespace vbsim {

namespace {

/// Reads the values of the data section in file order, binary or ascii.
class PlyValues {
 public:
  PlyValues(std::string_view data, PlyFormat format, const std::string& path)
      : data_(data), format_(format), path_(path) {}

  /// The next value of type `t` (integers exactly, floats as the file rounds them).
  double next(PlyType t) {
    return format_ == PlyFormat::Ascii ? next_ascii(t) : next_binary(t);
  }
  /// The next list count: an integer of type `t`, >= 0.
  uint64_t next_count(PlyType t) {
    const double v = next(t);
    if (v < 0) fail(fmt::format("list count {} is negative", v));
    return static_cast<uint64_t>(v);
  }
  /// Bytes (binary) or characters (ascii) not read yet.
  size_t remaining() const { return data_.size() - at_; }
  /// Throws unless only white space (ascii) or nothing (binary) is left.
  void expect_end() {
    if (format_ == PlyFormat::Ascii) skip_space();
    if (at_ != data_.size())
      fail(fmt::format("{} more bytes after the last element: the header's counts do not cover the file",
                       data_.size() - at_));
  }
  /// Where reading is now, for messages: instance `index` of element `e`
  /// (index -1: the element as a whole; e null: after the last element).
  void set_place(const PlyElement* e, int64_t index) {
    element_ = e;
    index_ = index;
  }
  [[noreturn]] void fail(const std::string& why) const {
    std::string place = "after the last element";
    if (element_ && index_ < 0) place = fmt::format("element '{}'", element_->name);
    if (element_ && index_ >= 0) place = fmt::format("element '{}' {} of {}", element_->name, index_, element_->count);
    throw SceneError(fmt::format("scene '{}': PLY {}: {}", path_, place, why));
  }

 private:
  double next_binary(PlyType t) {
    const size_t n = ply_type_bytes(t);
    if (remaining() < n) fail("the file ends inside this element (truncated)");
    unsigned char b[8];
    std::memcpy(b, data_.data() + at_, n);
    at_ += n;
    if (format_ == PlyFormat::BinaryBigEndian)
      for (size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    switch (t) {
      case PlyType::Int8: return static_cast<int8_t>(b[0]);
      case PlyType::Uint8: return b[0];
      case PlyType::Int16: { int16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::Uint16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::Int32: { int32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::Uint32: { uint32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::Float32: { float v; std::memcpy(&v, b, 4); return v; }
      case PlyType::Float64: { double v; std::memcpy(&v, b, 8); return v; }
    }
    return 0;
  }

  void skip_space() {
    while (at_ < data_.size() && (data_[at_] == ' ' || data_[at_] == '\t' || data_[at_] == '\r' || data_[at_] == '\n'))
      ++at_;
  }

  double next_ascii(PlyType t) {
    skip_space();
    const size_t start = at_;
    while (at_ < data_.size() && !(data_[at_] == ' ' || data_[at_] == '\t' || data_[at_] == '\r' || data_[at_] == '\n'))
      ++at_;
    if (at_ == start) fail("the file ends inside this element (truncated)");
    const std::string token(data_.substr(start, at_ - start));
    char* stop = nullptr;
    errno = 0;
    if (ply_type_is_integer(t)) {
      const long long v = std::strtoll(token.c_str(), &stop, 10);
      if (*stop != '\0' || errno == ERANGE || v < type_min(t) || v > type_max(t))
        fail(fmt::format("'{}' is not an integer of the property's type", token));
      return static_cast<double>(v);
    }
    // float: one rounding from the decimal to float32, as the file means it
    const double v = t == PlyType::Float32 ? std::strtof(token.c_str(), &stop) : std::strtod(token.c_str(), &stop);
    if (*stop != '\0') fail(fmt::format("'{}' is not a number", token));
    return v;
  }

  static long long type_min(PlyType t) {
    switch (t) {
      case PlyType::Int8: return -128;
      case PlyType::Int16: return -32768;
      case PlyType::Int32: return std::numeric_limits<int32_t>::min();
      default: return 0;
    }
  }
  static long long type_max(PlyType t) {
    switch (t) {
      case PlyType::Int8: return 127;
      case PlyType::Uint8: return 255;
      case PlyType::Int16: return 32767;
      case PlyType::Uint16: return 65535;
      case PlyType::Int32: return std::numeric_limits<int32_t>::max();
      default: return std::numeric_limits<uint32_t>::max();
    }
  }

  std::string_view data_;
  PlyFormat format_;
  const std::string& path_;
  size_t at_ = 0;
  const PlyElement* element_ = nullptr;
  int64_t index_ = -1;
};

/// The most instances of `e` that `bytes` bytes can hold: each value takes
/// its type's bytes (binary), or a character and a separator (ascii, the
/// file's last value without its separator).
uint64_t max_instances(const PlyElement& e, PlyFormat format, uint64_t bytes) {
  uint64_t least = 0;
  for (const PlyProperty& p : e.properties)
    least += format == PlyFormat::Ascii ? 2 : ply_type_bytes(p.is_list ? p.count_type : p.type);
  return format == PlyFormat::Ascii ? (bytes + 1) / least : bytes / least;
}

/// Splits polygon `v` (vertex indices) into triangles, appended to `out` (see the header).
void triangulate(const std::vector<uint32_t>& v, const std::vector<Vec3f>& pos,
                 std::vector<std::array<uint32_t, 3>>& out) {
  const size_t n = v.size();
  if (n < 3) return;
  size_t first = 0;
  if (n == 4) {
    // The quad's orientation (Newell's normal), then a vertex turning the other way is reflex.
    Vec3f normal{};
    for (size_t i = 0; i < 4; ++i) normal = normal + cross(pos[v[i]], pos[v[(i + 1) % 4]]);
    for (size_t i = 0; i < 4; ++i) {
      const Vec3f in = pos[v[i]] - pos[v[(i + 3) % 4]], out_edge = pos[v[(i + 1) % 4]] - pos[v[i]];
      if (dot(cross(in, out_edge), normal) < 0.0f) {
        first = i;
        break;
      }
    }
  }
  for (size_t k = 1; k + 1 < n; ++k) out.push_back({v[first], v[(first + k) % n], v[(first + k + 1) % n]});
}

}  // namespace

PlyMesh read_ply_mesh(std::string_view bytes, const std::string& path) {
  const PlyHeader h = parse_ply_header(bytes, path);
  PlyValues values(bytes.substr(h.data_offset), h.format, path);
  PlyMesh mesh;
  std::vector<uint32_t> polygon_indices;  // every face's vertex indices, one after the other
  std::vector<size_t> polygon_ends;       // where each face's indices end in polygon_indices
  bool vertices_seen = false;
  for (const PlyElement& e : h.elements) {
    values.set_place(&e, -1);
    if (e.name == "tristrips") values.fail("triangle strips are not supported; write faces instead");
    if (e.count == 0 || e.properties.empty()) continue;  // nothing to read
    const uint64_t most = max_instances(e, h.format, values.remaining());
    if (e.count > most)
      values.fail(fmt::format("the header declares {} of them, but the {} bytes left hold at most {}", e.count,
                              values.remaining(), most));
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    int xyz[3] = {-1, -1, -1}, nxyz[3] = {-1, -1, -1}, indices = -1;
    if (is_vertex) {
      if (vertices_seen) values.fail("a second vertex element");
      vertices_seen = true;
      const char* names[3] = {"x", "y", "z"};
      const char* nnames[3] = {"nx", "ny", "nz"};
      for (int k = 0; k < 3; ++k) {
        xyz[k] = e.find(names[k]);
        nxyz[k] = e.find(nnames[k]);
        if (xyz[k] < 0 || e.properties[xyz[k]].is_list)
          values.fail(fmt::format("no scalar property '{}'", names[k]));
      }
      const bool any_normal = nxyz[0] >= 0 || nxyz[1] >= 0 || nxyz[2] >= 0;
      const bool all_normals = nxyz[0] >= 0 && nxyz[1] >= 0 && nxyz[2] >= 0;
      if (any_normal && !all_normals) values.fail("normals need all of nx, ny and nz");
      for (int k = 0; k < 3 && all_normals; ++k)
        if (e.properties[nxyz[k]].is_list) values.fail(fmt::format("'{}' must be a scalar", nnames[k]));
      mesh.positions.reserve(e.count);
      if (all_normals) mesh.normals.reserve(e.count);
    }
    if (is_face) {
      indices = e.find("vertex_indices");
      if (indices < 0) indices = e.find("vertex_index");
      if (indices < 0 || !e.properties[indices].is_list)
        values.fail("no list property 'vertex_indices' (or 'vertex_index')");
      if (!ply_type_is_integer(e.properties[indices].type)) values.fail("vertex indices must be integers");
      polygon_ends.reserve(e.count);
    }
    for (uint64_t i = 0; i < e.count; ++i) {
      values.set_place(&e, static_cast<int64_t>(i));
      double scalar[64];
      for (size_t p = 0; p < e.properties.size(); ++p) {
        const PlyProperty& prop = e.properties[p];
        if (!prop.is_list) {
          const double v = values.next(prop.type);
          if (p < 64) scalar[p] = v;
          continue;
        }
        const uint64_t n = values.next_count(prop.count_type);
        const bool wanted = static_cast<int>(p) == indices;
        if (n > values.remaining()) values.fail(fmt::format("a list of {} values is longer than the file", n));
        for (uint64_t k = 0; k < n; ++k) {
          const double v = values.next(prop.type);
          if (!wanted) continue;
          if (v < 0) values.fail(fmt::format("vertex index {} is negative", v));
          if (v > std::numeric_limits<uint32_t>::max()) values.fail(fmt::format("vertex index {} is too large", v));
          polygon_indices.push_back(static_cast<uint32_t>(v));
        }
      }
      if (is_vertex) {
        const auto get = [&](int prop) {
          if (prop >= 64) values.fail("more than 64 properties before a coordinate");
          return static_cast<float>(scalar[prop]);
        };
        mesh.positions.push_back({get(xyz[0]), get(xyz[1]), get(xyz[2])});
        if (nxyz[0] >= 0) mesh.normals.push_back({get(nxyz[0]), get(nxyz[1]), get(nxyz[2])});
      } else if (is_face) {
        polygon_ends.push_back(polygon_indices.size());
      }
    }
  }
  values.set_place(nullptr, -1);
  values.expect_end();
  // Indices are checked once every vertex is known (PLY allows faces before vertices).
  size_t begin = 0;
  std::vector<uint32_t> polygon;
  for (size_t f = 0; f < polygon_ends.size(); ++f) {
    polygon.assign(polygon_indices.begin() + begin, polygon_indices.begin() + polygon_ends[f]);
    begin = polygon_ends[f];
    for (uint32_t index : polygon)
      if (index >= mesh.positions.size())
        throw SceneError(fmt::format("scene '{}': PLY face {} refers to vertex {}, but the file has {} vertices",
                                     path, f, index, mesh.positions.size()));
    triangulate(polygon, mesh.positions, mesh.triangles);
  }
  return mesh;
}

}  // namespace vbsim
