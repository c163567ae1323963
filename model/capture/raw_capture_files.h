// The capture shim's files in a raw directory, found by name and opened:
// per process image (a process, or each program it exec()s in turn) its
// summary, its threads' ray files (memory-mapped, read in place) and its
// scene snapshots (names and layouts: raw_capture_format.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <utility>

#include "capture/raw_capture_format.h"

namespace vbsim::capture {

/// One process image: its pid and its number g among the images of that pid
/// (0 the first; an exec'd program, or a later process with a reused pid, the next).
struct ProcessImage {
  long pid = 0;
  unsigned image = 0;
  bool operator<(const ProcessImage& o) const { return std::tie(pid, image) < std::tie(o.pid, o.image); }
  bool operator==(const ProcessImage& o) const { return pid == o.pid && image == o.image; }
  /// "<pid>.<g>", as its files are named.
  std::string name() const { return std::to_string(pid) + "." + std::to_string(image); }
};

struct ProcessFiles {
  ProcessImage id;
  std::string summary;                                   ///< process-<image>.txt, empty when missing
  std::map<int, std::string> ray_files;                  ///< thread index -> rays-<image>-<k>.bin
  std::map<std::pair<uint32_t, uint32_t>, std::string> scenes;  ///< (scene, commit) -> snapshot
  std::string refusal;                                   ///< refused-<image>.txt, empty when none
};

/// Every process image that left files in `dir`. Throws std::runtime_error
/// naming the directory when it cannot be read.
std::map<ProcessImage, ProcessFiles> find_capture_files(const std::string& dir);

/// Why the shim refused to capture process images in `dir` (refused-<image>.txt),
/// one "process P: reason" per image joined by "; ", or "" when it refused none.
std::string read_refusals(const std::string& dir);

/// The "key value" lines of a process summary; throws naming the file when
/// unreadable. A summary without "complete 1" is one the image never finished
/// (it claimed its name and then died or was killed).
std::map<std::string, uint64_t> read_process_summary(const std::string& path);

/// A ray file mapped read-only; a size that is not a whole number of records
/// is an error naming the file.
class MappedRays {
 public:
  explicit MappedRays(const std::string& path);
  ~MappedRays();
  MappedRays(MappedRays&& o) noexcept;
  MappedRays& operator=(MappedRays&&) = delete;
  MappedRays(const MappedRays&) = delete;

  const RawRay* data() const { return rays_; }
  std::size_t size() const { return count_; }
  const RawRay& operator[](std::size_t i) const { return rays_[i]; }

 private:
  const RawRay* rays_ = nullptr;
  std::size_t count_ = 0;
  void* map_ = nullptr;
  std::size_t bytes_ = 0;
};

}  // namespace vbsim::capture
