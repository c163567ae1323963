// Helpers shared by the trace tests: a per-test temporary directory, file
// I/O, bit-exact ray comparison and catching the TraceError a call throws.
#pragma once
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>
#include <vector>

#include "trace/trace_error.h"
#include "trace/trace_file.h"
#include "trace/trace_record.h"
#include "trace/trace_source.h"

namespace vbsim::test {

/// A fresh directory under the system temp directory, removed on destruction.
/// The name includes the process id: ctest may run test cases in parallel.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : dir_(std::filesystem::temp_directory_path() /
             ("vbsim-" + name + "-" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

 private:
  std::filesystem::path dir_;
};

inline void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  REQUIRE(out.good());
}

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in.good());
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline std::vector<TraceRay> read_all(TraceSource& source) {
  std::vector<TraceRay> rays;
  TraceRay ray;
  while (source.next(ray)) rays.push_back(ray);
  return rays;
}

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

inline bool same_bits(Vec3f a, Vec3f b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

/// Field-by-field equality with floats compared bit for bit (so -0 != +0).
inline bool same_ray(const TraceRay& a, const TraceRay& b) {
  return a.id == b.id && a.parent == b.parent && a.kind == b.kind && same_bits(a.o, b.o) &&
         same_bits(a.d, b.d) && same_bits(a.tmin, b.tmin) && same_bits(a.tmax, b.tmax) &&
         a.parent_prim == b.parent_prim && a.has_parent_t == b.has_parent_t &&
         (!a.has_parent_t || same_bits(a.parent_t, b.parent_t)) &&
         a.has_parent_uv == b.has_parent_uv &&
         (!a.has_parent_uv ||
          (same_bits(a.parent_u, b.parent_u) && same_bits(a.parent_v, b.parent_v))) &&
         a.has_parent_ns == b.has_parent_ns &&
         (!a.has_parent_ns || same_bits(a.parent_ns, b.parent_ns)) && a.sign == b.sign &&
         a.has_expect == b.has_expect && (!a.has_expect || a.expect_prim == b.expect_prim) &&
         a.has_expect_t == b.has_expect_t && (!a.has_expect_t || same_bits(a.expect_t, b.expect_t));
}

/// Runs `f` and returns the TraceError it throws; fails the test if it throws none.
template <class F>
TraceError trace_error_of(F&& f) {
  try {
    f();
  } catch (const TraceError& e) {
    return e;
  }
  FAIL("expected a TraceError");
  throw std::logic_error("unreachable");
}

/// The error reading every ray of the trace at `path` throws.
inline TraceError error_reading(const std::string& path) {
  auto source = open_trace(path);
  return trace_error_of([&] { read_all(*source); });
}

}  // namespace vbsim::test
