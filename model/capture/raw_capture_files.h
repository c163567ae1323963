// The capture shim's files in a raw directory, found by name and opened:
// per process its summary, its threads' ray files (memory-mapped, read in
// place) and its scene snapshots (layouts: raw_capture_format.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "capture/raw_capture_format.h"

namespace vbsim::capture {

struct ProcessFiles {
  long pid = 0;
  std::string summary;                                   ///< process-<pid>.txt, empty when missing
  std::map<int, std::string> ray_files;                  ///< thread index -> rays-<pid>-<k>.bin
  std::map<std::pair<uint32_t, uint32_t>, std::string> scenes;  ///< (scene, commit) -> snapshot
};

/// Every process that left files in `dir`, by pid. Throws std::runtime_error
/// naming the directory when it cannot be read.
std::map<long, ProcessFiles> find_capture_files(const std::string& dir);

/// The "key value" lines of a process summary; throws naming the file when unreadable.
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
