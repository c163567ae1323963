// VcdChangeLog: the VCD's value changes, added in any order of cycles and read
// back in cycle order, in bounded memory: every `chunk` changes are sorted and
// spilled to an anonymous temporary file (std::tmpfile, removed when closed);
// reading merges the sorted runs. Changes of one cycle come back in no
// particular order (the VCD sums them).
#pragma once
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

namespace vbsim::hw {

class VcdChangeLog {
 public:
  struct Change {
    uint64_t cycle;
    uint32_t id;
    int64_t delta;
  };

  explicit VcdChangeLog(size_t chunk = size_t{1} << 20) : chunk_(chunk) {}
  ~VcdChangeLog();
  VcdChangeLog(const VcdChangeLog&) = delete;
  VcdChangeLog& operator=(const VcdChangeLog&) = delete;

  void add(const Change& c) {
    buffer_.push_back(c);
    if (__builtin_expect(buffer_.size() >= chunk_, 0)) spill();
  }
  size_t spilled_runs() const { return runs_.size(); }

  /// Ends adding: the changes are read back in cycle order by next().
  void finish_adding();
  /// The next change in cycle order; false when none is left. Throws
  /// std::runtime_error when the temporary file cannot be read.
  bool next(Change& c);

 private:
  struct Run {
    long offset;        ///< in the temporary file
    size_t left;        ///< changes not yet read into `buffer`
    std::vector<Change> buffer;
    size_t at = 0;      ///< next in `buffer`
  };
  void spill();
  bool refill(Run& r);

  size_t chunk_;
  std::vector<Change> buffer_;
  std::FILE* file_ = nullptr;
  std::vector<Run> runs_;
  std::vector<uint32_t> heap_;  ///< runs with changes left, a min-heap by their next change's cycle
  bool reading_ = false;
};

}  // namespace vbsim::hw
