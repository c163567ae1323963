// TimelineRecorder: busy intervals of module instances in a window of cycles,
// written as Chrome trace-event JSON (open in Perfetto or chrome://tracing).
// 1 us on the viewer's axis is one cycle. An interval is kept when it starts in
// the window; a TraceScope keeps only the instances it names.
//
// Processes are module instances ("accelerator.core_0"); a track asked for by
// track() ("slot 3", "box_unit", "memory reads", "dram requests") is a group of
// lanes, each a thread of its process: an interval goes to the lowest lane
// whose intervals all end by its start, so that no two intervals of one thread
// overlap (a pipelined unit with N operations in flight shows N lanes). Lane 0
// is named as the track, lane k > 0 "TRACK #k".
//
// Streamed: every interval is written when it is added (it is final then: the
// model adds an interval once its end is known), through an AtomicOutputFile
// named only by finish(). Memory is bounded by the number of lanes, not the
// length of the run; a run that throws or is killed leaves no file.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hw/observe/trace_scope.h"

namespace vbsim {
class AtomicOutputFile;
}

namespace vbsim::hw {

class TimelineRecorder {
 public:
  static constexpr uint32_t kNoTrack = ~uint32_t{0};

  /// Starts writing `path` (its temporary; throws OutputError when it cannot be created).
  TimelineRecorder(const std::string& path, uint64_t first, uint64_t cycles, TraceScope scope);
  ~TimelineRecorder();

  /// The track `thread` of process `process`: its id, or kNoTrack when
  /// `instance` (the process when empty) is outside the scope.
  uint32_t track(const std::string& process, const std::string& thread, const std::string& instance = "");
  /// `name` ("node", "leaf", "box", "triangle", "avoidance", "read", "dram"...)
  /// busy on `track` over [start, end); `ray` the ray's id (-1: none). `name`
  /// is a literal (written as is, unescaped).
  void add(uint32_t track, const char* name, uint64_t start, uint64_t end, int64_t ray) {
    if (track == kNoTrack || start < first_ || start >= end_) return;
    write_event(track, name, start, end, ray);
  }
  bool in_window(uint64_t start) const { return start >= first_ && start < end_; }
  uint64_t events() const { return events_; }
  /// Lanes (threads) written so far.
  size_t lanes() const { return lanes_; }
  /// Ends the JSON and names the file; throws OutputError when it cannot be written.
  void finish();

 private:
  struct Track {
    uint32_t pid;
    uint32_t order;                  ///< creation order within its process (threads' sort order)
    std::string name;
    std::vector<uint64_t> free_from;  ///< by lane: the end of its last interval
    std::vector<uint32_t> tid;        ///< by lane: its thread id
  };
  void write_event(uint32_t track, const char* name, uint64_t start, uint64_t end, int64_t ray);
  uint32_t new_lane(Track& t);
  void put(const std::string& text);
  void flush();

  uint64_t first_, end_;
  TraceScope scope_;
  std::unique_ptr<AtomicOutputFile> file_;
  std::string buffer_;  ///< events not yet handed to the file
  std::vector<std::string> processes_;  ///< by pid
  std::vector<uint32_t> threads_;       ///< by pid: threads (lanes) so far
  std::vector<uint32_t> tracks_in_;     ///< by pid: tracks so far
  std::vector<Track> tracks_;
  uint64_t events_ = 0;
  size_t lanes_ = 0;
  bool first_event_ = true;
};

}  // namespace vbsim::hw
