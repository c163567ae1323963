// TimelineRecorder: busy intervals of module instances in a window of cycles,
// written as Chrome trace-event JSON (open in Perfetto or chrome://tracing).
// A track is a thread of a process; processes are module instances
// ("accelerator.core_0"), threads their ray slots and units ("slot 3",
// "triangle_tester"), named by metadata events. 1 us on the viewer's axis is
// one cycle. An interval is kept when it starts in the window; a scope prefix
// keeps only the instances below it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace vbsim::hw {

class TimelineRecorder {
 public:
  static constexpr uint32_t kNoTrack = ~uint32_t{0};

  TimelineRecorder(uint64_t first, uint64_t cycles, std::string scope);

  /// The track `thread` of instance `process`: its id, or kNoTrack outside the scope.
  uint32_t track(const std::string& process, const std::string& thread);
  /// `name` ("node", "leaf", "box", "triangle", "avoidance", "read", "dram"...)
  /// busy on `track` over [start, end); `ray` the ray's id (-1: none).
  void add(uint32_t track, const char* name, uint64_t start, uint64_t end, int64_t ray) {
    if (track == kNoTrack || start < first_ || start >= end_) return;
    events_.push_back({name, track, start, end, ray});
  }
  bool in_window(uint64_t start) const { return start >= first_ && start < end_; }
  size_t events() const { return events_.size(); }
  /// Writes the JSON; throws std::runtime_error when the file cannot be written.
  void write(const std::string& path) const;

 private:
  struct Event {
    const char* name;
    uint32_t track;
    uint64_t start, end;
    int64_t ray;
  };
  struct Track {
    uint32_t pid, tid;
  };
  uint64_t first_, end_;
  std::string scope_;
  std::vector<std::string> processes_;   // by pid
  std::vector<std::vector<std::string>> threads_;  // by pid, then tid
  std::vector<Track> tracks_;
  std::vector<Event> events_;
};

}  // namespace vbsim::hw
