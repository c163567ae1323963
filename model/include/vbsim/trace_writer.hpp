// vbsim trace writer: header-only, C++17 standard library only. Writes the
// vbsim ray trace format (docs/trace-format.md) in its text form (.jsonl) or
// its binary form (.vbt, docs/trace-binary.md), chosen by the file name as
// vbsim chooses it. Copy this one file into a renderer to emit traces:
//
//   vbsim::writer::TraceWriter w("out.jsonl", {"bunny.obj"});
//   vbsim::writer::Ray r;
//   r.id = 0; r.o = {0, 5, 20}; r.d = {0, 0, -1};
//   w.write(r);
//   w.close();
//
// Every float is written so that it reads back bit for bit. write() applies
// the format's per-ray rules and refuses a child whose parent id is not below
// its own while ids ascend (a parent must precede its children); errors are
// TraceWriteError naming the file, the ray's line or record and the field.
// The file is written as NAME.partial and gets its name in close(); a writer
// destroyed without close() removes the partial file.
#pragma once
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <unordered_set>
#include <vector>

namespace vbsim::writer {

enum class Kind : uint8_t { Primary = 0, Reflect = 1, Refract = 2, Diffuse = 3, Shadow = 4 };

/// One ray, field for field as the trace format defines it; optional fields are absent when empty.
struct Ray {
  int64_t id = 0;
  int64_t parent = -1;  ///< -1: a camera ray
  Kind kind = Kind::Primary;
  std::array<float, 3> o{};  ///< origin, before any self-intersection offset
  std::array<float, 3> d{};  ///< direction, non-zero, need not be unit length
  float tmin = 0.0f;
  float tmax = std::numeric_limits<float>::infinity();
  int32_t parent_prim = -1;  ///< triangle the parent ray hit
  std::optional<float> parent_t;
  std::optional<std::array<float, 2>> parent_uv;  ///< p = (1-u-v) v0 + u v1 + v v2
  std::optional<std::array<float, 3>> parent_ns;
  std::optional<int> sign;          ///< 1 when dot(d, Ng(parent_prim)) < 0, else 0
  std::optional<int32_t> expect_prim;  ///< the exact answer: a triangle, or -1 for a miss
  std::optional<double> expect_t;      ///< its distance (only with a hit)
  /// Why the renderer's answer depends on what the trace does not hold: bit k
  /// is reason k of detail::incomplete_name (0: none; docs/trace-format.md).
  uint32_t incomplete = 0;
};

struct Header {
  /// `Header{"bunny.obj"}`: a header naming only the scene.
  Header(std::string scene_path = "") : scene(std::move(scene_path)) {}
  std::string scene;  ///< path of the scene relative to the trace file
  std::optional<std::array<float, 3>> light;
  std::string generator, description;             ///< left out when empty
  std::optional<std::array<float, 16>> transform;  ///< row-major 4x4, applied to every vertex
};

struct TraceWriteError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

namespace detail {

/// Name of `incomplete` bit k (11 reasons).
inline const char* incomplete_name(unsigned k) {
  static const char* const names[] = {"instance", "quad", "grid",        "subdivision",    "curve", "point",
                                      "user",     "motion_blur", "other_geometry", "filter", "mask"};
  return k < 11 ? names[k] : nullptr;
}
inline const char* kind_name(Kind k) {
  static const char* const names[] = {"primary", "reflect", "refract", "diffuse", "shadow"};
  return static_cast<unsigned>(k) < 5 ? names[static_cast<unsigned>(k)] : nullptr;
}

/// Shortest decimal that reads back to `x` whichever way a reader rounds: a
/// shortest float32 decimal whose double lies exactly halfway between `x` and
/// a neighbour (a reader that parses a double and rounds it could pick the
/// neighbour) is replaced by the exact double; -0 keeps its sign as "-0.0".
inline std::string float_text(float x) {
  if (x == 0.0f && std::signbit(x)) return "-0.0";
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, x);
  double back = 0.0;
  std::from_chars(buf, r.ptr, back);
  if (static_cast<float>(back) != x || (static_cast<double>(std::nextafter(x, INFINITY)) + x) / 2 == back ||
      (static_cast<double>(std::nextafter(x, -INFINITY)) + x) / 2 == back)
    r = std::to_chars(buf, buf + sizeof buf, static_cast<double>(x));
  return std::string(buf, r.ptr);
}

inline std::string double_text(double x) {
  if (x == 0.0 && std::signbit(x)) return "-0.0";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

inline std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char esc[8];
      std::snprintf(esc, sizeof esc, "\\u%04x", c);
      out += esc;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

template <std::size_t N>
std::string float_array(const std::array<float, N>& a) {
  std::string out = "[";
  for (std::size_t i = 0; i < N; ++i) out += (i ? "," : "") + float_text(a[i]);
  return out + "]";
}

template <std::size_t N>
bool all_finite(const std::array<float, N>& a) {
  for (float x : a)
    if (!std::isfinite(x)) return false;
  return true;
}

inline void put_u32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xffu);
}
inline void put_u64(std::string& out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out += static_cast<char>((v >> (8 * i)) & 0xffu);
}
inline void put_f32(std::string& out, float x) {
  uint32_t b;
  std::memcpy(&b, &x, 4);
  put_u32(out, b);
}

}  // namespace detail

class TraceWriter {
 public:
  /// Creates `path` (binary when it ends in ".vbt") and writes the header.
  TraceWriter(std::string path, const Header& header)
      : path_(std::move(path)), partial_(path_ + ".partial"),
        binary_(path_.size() >= 4 && path_.compare(path_.size() - 4, 4, ".vbt") == 0) {
    if (header.scene.empty()) fail_header("scene", "is empty");
    std::string json = "{\"format\":\"vbsim-trace\",\"version\":1,\"scene\":" + detail::json_string(header.scene);
    if (header.light) {
      if (!detail::all_finite(*header.light)) fail_header("light", "is not finite");
      json += ",\"light\":" + detail::float_array(*header.light);
    }
    if (!header.generator.empty()) json += ",\"generator\":" + detail::json_string(header.generator);
    if (!header.description.empty()) json += ",\"description\":" + detail::json_string(header.description);
    if (header.transform) {
      if (!detail::all_finite(*header.transform)) fail_header("transform", "is not finite");
      json += ",\"transform\":" + detail::float_array(*header.transform);
    }
    json += "}";
    out_.open(partial_, std::ios::binary | std::ios::trunc);
    if (!out_) throw TraceWriteError(partial_ + ": cannot create");
    if (binary_) {
      std::string pre = "VBSIMTRB";
      detail::put_u32(pre, 1);
      detail::put_u32(pre, static_cast<uint32_t>(json.size()));
      json.append((8 - json.size() % 8) % 8, ' ');
      emit(pre + json);
    } else {
      emit(json + "\n");
    }
  }
  TraceWriter(const TraceWriter&) = delete;
  TraceWriter& operator=(const TraceWriter&) = delete;
  ~TraceWriter() {
    if (!closed_) {  // never finished: leave nothing that looks complete
      out_.close();
      std::remove(partial_.c_str());
    }
  }

  /// Appends one ray; throws TraceWriteError when it breaks the format's rules.
  void write(const Ray& r) {
    if (closed_) throw TraceWriteError(path_ + ": write after close");
    check(r);
    emit(binary_ ? record(r) : line(r));
    remember(r.id);
    last_id_ = r.id;
    ++count_;
  }

  /// Flushes, renames NAME.partial to NAME and returns the number of rays written.
  int64_t close() {
    if (closed_) return count_;
    out_.close();
    if (!out_) throw TraceWriteError(path_ + ": write failed");
    if (std::rename(partial_.c_str(), path_.c_str()) != 0)
      throw TraceWriteError(path_ + ": cannot rename " + partial_ + ": " + std::strerror(errno));
    closed_ = true;
    return count_;
  }

 private:
  [[noreturn]] void fail(const char* field, const std::string& message) const {
    const std::string place = binary_ ? "record " + std::to_string(count_) : "line " + std::to_string(count_ + 2);
    throw TraceWriteError(path_ + ": " + place + ": field '" + field + "': " + message);
  }
  [[noreturn]] void fail_header(const char* field, const std::string& message) const {
    throw TraceWriteError(path_ + ": header: field '" + field + "': " + message);
  }

  void check(const Ray& r) {
    if (r.id < 0) fail("id", std::to_string(r.id) + " is negative");
    if (r.parent < -1) fail("parent", "is below -1 (-1 means no parent)");
    if (count_ > 0 && r.id <= last_id_) ascending_ = false;
    if (r.parent == r.id || (ascending_ && r.parent > r.id))
      fail("parent", "ray " + std::to_string(r.id) + " names parent " + std::to_string(r.parent) +
                         ", which cannot come before it; a parent must precede its children");
    if (!detail::kind_name(r.kind)) fail("kind", "unknown kind");
    if (r.parent >= 0 && r.kind == Kind::Primary)
      fail("kind", "primary, but the ray has parent " + std::to_string(r.parent) +
                       ": a camera ray has no parent; give the child's kind (reflect, refract, diffuse or shadow)");
    if (seen_.count(r.id) || (r.id >= dense_begin_ && r.id < dense_end_))
      fail("id", std::to_string(r.id) + " was given before: ids are unique within a trace");
    if (!detail::all_finite(r.o)) fail("o", "is not finite");
    if (!detail::all_finite(r.d) || (r.d[0] == 0.0f && r.d[1] == 0.0f && r.d[2] == 0.0f))
      fail("d", "must be finite and non-zero");
    if (!std::isfinite(r.tmin) || r.tmin < 0.0f) fail("tmin", "must be finite and >= 0");
    if (std::isnan(r.tmax) || r.tmax < r.tmin) fail("tmax", "must not be NaN or below tmin");
    if (r.parent_prim < -1) fail("parent_prim", "is below -1");
    if (r.parent_t && !std::isfinite(*r.parent_t)) fail("parent_t", "is not finite");
    if (r.parent_uv && !detail::all_finite(*r.parent_uv)) fail("parent_uv", "is not finite");
    if (r.parent_ns && !detail::all_finite(*r.parent_ns)) fail("parent_ns", "is not finite");
    if (r.sign && *r.sign != 0 && *r.sign != 1) fail("sign", "must be 0 or 1");
    if (r.expect_prim && *r.expect_prim < -1) fail("expect.prim", "is below -1");
    if (r.expect_t && (!r.expect_prim || *r.expect_prim < 0 || !std::isfinite(*r.expect_t)))
      fail("expect.t", "a hit distance needs a hit (expect_prim >= 0) and must be finite");
    if (r.incomplete >> 11) fail("incomplete", "unknown reason bits");
  }
  /// Records `id` as written: ids that continue the run [dense_begin_, dense_end_) cost nothing.
  void remember(int64_t id) {
    if (dense_end_ < 0) {
      dense_begin_ = id;
      dense_end_ = id + 1;
    } else if (id == dense_end_) {
      ++dense_end_;
      while (seen_.erase(dense_end_)) ++dense_end_;
    } else {
      seen_.insert(id);
    }
  }

  /// The text form, laid out as vbsim's own writer does (fields in format order, defaults left out).
  static std::string line(const Ray& r) {
    std::string s = "{\"id\":" + std::to_string(r.id);
    if (r.parent != -1) s += ",\"parent\":" + std::to_string(r.parent);
    if (r.kind != Kind::Primary) s += std::string(",\"kind\":\"") + detail::kind_name(r.kind) + "\"";
    s += ",\"o\":" + detail::float_array(r.o) + ",\"d\":" + detail::float_array(r.d);
    if (r.tmin != 0.0f || std::signbit(r.tmin)) s += ",\"tmin\":" + detail::float_text(r.tmin);
    if (!(std::isinf(r.tmax) && r.tmax > 0)) s += ",\"tmax\":" + detail::float_text(r.tmax);
    if (r.parent_prim != -1) s += ",\"parent_prim\":" + std::to_string(r.parent_prim);
    if (r.parent_t) s += ",\"parent_t\":" + detail::float_text(*r.parent_t);
    if (r.parent_uv) s += ",\"parent_uv\":" + detail::float_array(*r.parent_uv);
    if (r.parent_ns) s += ",\"parent_ns\":" + detail::float_array(*r.parent_ns);
    if (r.sign) s += ",\"sign\":" + std::to_string(*r.sign);
    if (r.expect_prim) {
      s += ",\"expect\":{\"prim\":" + std::to_string(*r.expect_prim);
      if (r.expect_t) s += ",\"t\":" + detail::double_text(*r.expect_t);
      s += "}";
    }
    if (r.incomplete) {
      s += ",\"incomplete\":[";
      for (unsigned k = 0, n = 0; k < 11; ++k)
        if (r.incomplete >> k & 1u) s += std::string(n++ ? ",\"" : "\"") + detail::incomplete_name(k) + "\"";
      s += "]";
    }
    return s + "}\n";
  }

  /// The 96-byte binary record (docs/trace-binary.md); absent fields stored as zeros (-1 in expect_prim).
  static std::string record(const Ray& r) {
    std::string b;
    b.reserve(96);
    detail::put_u64(b, static_cast<uint64_t>(r.id));
    detail::put_u64(b, static_cast<uint64_t>(r.parent));
    for (float x : r.o) detail::put_f32(b, x);
    for (float x : r.d) detail::put_f32(b, x);
    detail::put_f32(b, r.tmin);
    detail::put_f32(b, r.tmax);
    detail::put_u32(b, static_cast<uint32_t>(r.parent_prim));
    detail::put_f32(b, r.parent_t.value_or(0.0f));
    for (float x : r.parent_uv.value_or(std::array<float, 2>{})) detail::put_f32(b, x);
    for (float x : r.parent_ns.value_or(std::array<float, 3>{})) detail::put_f32(b, x);
    detail::put_u32(b, static_cast<uint32_t>(r.expect_prim.value_or(-1)));
    uint64_t t_bits = 0;
    const double t = r.expect_t.value_or(0.0);
    std::memcpy(&t_bits, &t, 8);
    detail::put_u64(b, t_bits);
    b += static_cast<char>(r.kind);
    b += static_cast<char>(r.sign.value_or(0));
    const uint32_t flags = (r.parent_t ? 0x01u : 0u) | (r.parent_uv ? 0x02u : 0u) | (r.parent_ns ? 0x04u : 0u) |
                           (r.expect_prim ? 0x08u : 0u) | (r.expect_t ? 0x10u : 0u) | (r.sign ? 0x20u : 0u);
    b += static_cast<char>(flags & 0xffu);
    b += static_cast<char>(flags >> 8);
    detail::put_u32(b, r.incomplete);
    return b;
  }

  void emit(const std::string& bytes) {
    out_.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out_) throw TraceWriteError(partial_ + ": write failed");
  }

  std::string path_, partial_;
  bool binary_;
  std::ofstream out_;
  int64_t count_ = 0;
  int64_t last_id_ = -1;
  bool ascending_ = true;
  bool closed_ = false;
  int64_t dense_begin_ = -1, dense_end_ = -1;  ///< every id in [begin, end) has been written
  std::unordered_set<int64_t> seen_;           ///< written ids outside that run

};

}  // namespace vbsim::writer
