#include "scene/obj_plain_reader.h"

#include <assimp/fast_atof.h>
#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "progress/work_progress.h"
#include "scene/scene_builder.h"

namespace vbsim {

namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }

/// What fast_atof throws on a string that is no number (never one validate_obj
/// passed): assimp's own exception type is not exported by its library.
struct NotANumber {
  template <typename... Parts>
  explicit NotANumber(Parts&&...) {}
};

/// One pass over validated lines; every statement starts its line (plain()).
class PlainObjReader {
 public:
  PlainObjReader(const std::string& path, const ObjSummary& summary, SceneBuilder& builder)
      : path_(path), builder_(builder), with_normals_(summary.every_face_names_normals()) {
    positions_.reserve(summary.vertices);
    builder_.reserve(summary.triangles);
  }

  void line(const char* p, const char* end, uint64_t number) {
    line_ = number;
    if (p == end || p[0] == '#') return;
    if (p[0] == 'v' && p + 1 < end && is_blank(p[1])) {
      positions_.push_back(vector3(p + 1, end));
    } else if (p[0] == 'v' && p + 2 < end && p[1] == 'n' && is_blank(p[2])) {
      normals_.push_back(vector3(p + 2, end));
    } else if (p[0] == 'f' && p + 1 < end && is_blank(p[1])) {
      face(p + 1, end);
    }  // vt, s and blank lines: nothing the scene keeps
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw SceneError(fmt::format("scene '{}': OBJ line {}: {}", path_, line_, why));
  }

  static const char* skip_blanks(const char* p, const char* end) {
    while (p < end && is_blank(*p)) ++p;
    return p;
  }

  /// Three numbers, each converted as assimp's OBJ parser converts it.
  Vec3f vector3(const char* p, const char* end) const {
    float c[3];
    for (int k = 0; k < 3; ++k) {
      p = skip_blanks(p, end);
      if (p == end) fail("fewer than three numbers");
      try {
        c[k] = Assimp::fast_atof<NotANumber>(p, &p);  // stops at the number's end: a blank, '\r', '\n' or the final NUL
      } catch (const NotANumber&) {
        fail("a coordinate that is not a number");
      }
      while (p < end && !is_blank(*p)) ++p;
    }
    return {c[0], c[1], c[2]};
  }

  /// An index of the reference at `p` (up to '/', a blank or the line's end),
  /// 0-based; negative ones count back from the `count` defined so far.
  size_t index(const char*& p, const char* end, size_t count, const char* what) const {
    const bool negative = p < end && *p == '-';
    if (negative) ++p;
    uint64_t value = 0;
    while (p < end && *p >= '0' && *p <= '9') value = value * 10 + static_cast<uint64_t>(*p++ - '0');
    if (value == 0 || value > count) fail(fmt::format("a {} index out of range", what));
    return negative ? count - value : value - 1;
  }

  void face(const char* p, const char* end) {
    Vec3f v[3], n[3];
    for (int k = 0; k < 3; ++k) {
      p = skip_blanks(p, end);
      v[k] = positions_[index(p, end, positions_.size(), "vertex")];
      if (p < end && *p == '/') {
        ++p;
        while (p < end && *p != '/' && !is_blank(*p)) ++p;  // the texture coordinate: not kept
        if (p < end && *p == '/') {
          ++p;
          const size_t normal = index(p, end, normals_.size(), "normal");
          if (with_normals_) n[k] = normals_[normal];
        }
      }
      while (p < end && !is_blank(*p)) ++p;
    }
    builder_.add(v, n, -2, line_);
  }

  const std::string& path_;
  SceneBuilder& builder_;
  bool with_normals_;
  std::vector<Vec3f> positions_, normals_;
  uint64_t line_ = 0;
};

}  // namespace

Scene read_plain_obj(const std::string& bytes, const std::string& path, const ObjSummary& summary,
                     const std::optional<std::array<float, 16>>& transform, WorkProgress* progress) {
  if (!summary.plain()) throw SceneError(fmt::format("scene '{}': not a plain OBJ file", path));
  SceneBuilder builder(path, transform, summary.every_face_names_normals());
  PlainObjReader reader(path, summary, builder);
  uint64_t number = 0;
  const char* at = bytes.data();
  const char* const stop = bytes.data() + bytes.size();
  const char* next_report = at;
  if (progress) progress->begin("reading triangles", megabytes(bytes.size()), "MB");
  while (at < stop) {
    if (progress && at >= next_report) {
      progress->update(megabytes(static_cast<size_t>(at - bytes.data())));
      next_report = at + (size_t{1} << 20);
    }
    const char* end = static_cast<const char*>(std::memchr(at, '\n', static_cast<size_t>(stop - at)));
    if (end == nullptr) end = stop;
    const char* content_end = end > at && end[-1] == '\r' ? end - 1 : end;
    reader.line(at, content_end, ++number);
    at = end + 1;
  }
  return builder.finish();
}

}  // namespace vbsim
