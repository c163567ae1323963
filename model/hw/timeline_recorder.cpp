#include "hw/timeline_recorder.h"

#include "io/atomic_output_file.h"

#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace vbsim::hw {

TimelineRecorder::TimelineRecorder(uint64_t first, uint64_t cycles, std::string scope)
    : first_(first), end_(first + cycles), scope_(std::move(scope)) {}

uint32_t TimelineRecorder::track(const std::string& process, const std::string& thread) {
  if (!scope_.empty() && process.compare(0, scope_.size(), scope_) != 0) return kNoTrack;
  uint32_t pid = 0;
  while (pid < processes_.size() && processes_[pid] != process) ++pid;
  if (pid == processes_.size()) {
    processes_.push_back(process);
    threads_.emplace_back();
  }
  threads_[pid].push_back(thread);
  tracks_.push_back({pid, static_cast<uint32_t>(threads_[pid].size() - 1)});
  return static_cast<uint32_t>(tracks_.size() - 1);
}

void TimelineRecorder::write(const std::string& path) const {
  nlohmann::json list = nlohmann::json::array();
  for (uint32_t pid = 0; pid < processes_.size(); ++pid) {
    list.push_back({{"name", "process_name"}, {"ph", "M"}, {"pid", pid}, {"args", {{"name", processes_[pid]}}}});
    list.push_back({{"name", "process_sort_index"}, {"ph", "M"}, {"pid", pid}, {"args", {{"sort_index", pid}}}});
    for (uint32_t tid = 0; tid < threads_[pid].size(); ++tid) {
      list.push_back({{"name", "thread_name"}, {"ph", "M"}, {"pid", pid}, {"tid", tid},
                      {"args", {{"name", threads_[pid][tid]}}}});
      list.push_back({{"name", "thread_sort_index"}, {"ph", "M"}, {"pid", pid}, {"tid", tid},
                      {"args", {{"sort_index", tid}}}});
    }
  }
  for (const Event& e : events_) {
    const Track& t = tracks_[e.track];
    nlohmann::json ev = {{"name", e.name}, {"ph", "X"},    {"ts", e.start},
                         {"dur", e.end - e.start}, {"pid", t.pid}, {"tid", t.tid}};
    if (e.ray >= 0) ev["args"] = {{"ray", e.ray}};
    list.push_back(std::move(ev));
  }
  write_output_file(path, nlohmann::json{{"traceEvents", list}, {"displayTimeUnit", "ns"}}.dump() + "\n", "timeline");
}

}  // namespace vbsim::hw
