#include "hw/observe/timeline_recorder.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "io/atomic_output_file.h"

namespace vbsim::hw {

namespace {
constexpr size_t kFlushBytes = 1 << 16;
std::string quoted(const std::string& s) { return nlohmann::json(s).dump(); }
}  // namespace

TimelineRecorder::TimelineRecorder(const std::string& path, uint64_t first, uint64_t cycles, TraceScope scope)
    : first_(first), end_(first + cycles < first ? ~uint64_t{0} : first + cycles), scope_(std::move(scope)),
      file_(std::make_unique<AtomicOutputFile>(path)) {
  buffer_ = "{\"displayTimeUnit\":\"ns\",\"traceEvents\":[\n";
}

TimelineRecorder::~TimelineRecorder() = default;  // unfinished: the temporary is removed

uint32_t TimelineRecorder::track(const std::string& process, const std::string& thread, const std::string& instance) {
  if (!scope_.matches(instance.empty() ? process : instance)) return kNoTrack;
  uint32_t pid = 0;
  while (pid < processes_.size() && processes_[pid] != process) ++pid;
  if (pid == processes_.size()) {
    processes_.push_back(process);
    threads_.push_back(0);
    tracks_in_.push_back(0);
    put(fmt::format(R"({{"name":"process_name","ph":"M","pid":{},"args":{{"name":{}}}}})", pid, quoted(process)));
    put(fmt::format(R"({{"name":"process_sort_index","ph":"M","pid":{},"args":{{"sort_index":{}}}}})", pid, pid));
  }
  tracks_.push_back({pid, tracks_in_[pid]++, thread, {}, {}});
  return static_cast<uint32_t>(tracks_.size() - 1);
}

uint32_t TimelineRecorder::new_lane(Track& t) {
  const uint32_t lane = static_cast<uint32_t>(t.tid.size());
  const uint32_t tid = threads_[t.pid]++;
  t.tid.push_back(tid);
  t.free_from.push_back(0);
  ++lanes_;
  const std::string name = lane == 0 ? t.name : fmt::format("{} #{}", t.name, lane);
  put(fmt::format(R"({{"name":"thread_name","ph":"M","pid":{},"tid":{},"args":{{"name":{}}}}})", t.pid, tid,
                  quoted(name)));
  // Lanes of a track side by side, tracks in the order they were made.
  put(fmt::format(R"({{"name":"thread_sort_index","ph":"M","pid":{},"tid":{},"args":{{"sort_index":{}}}}})", t.pid,
                  tid, uint64_t{t.order} * 65536 + lane));
  return lane;
}

void TimelineRecorder::write_event(uint32_t track, const char* name, uint64_t start, uint64_t end, int64_t ray) {
  Track& t = tracks_[track];
  // The lowest lane free at `start`: every interval on it ends by then.
  uint32_t lane = 0;
  while (lane < t.free_from.size() && t.free_from[lane] > start) ++lane;
  if (lane == t.free_from.size()) new_lane(t);
  t.free_from[lane] = std::max(t.free_from[lane], end);
  ++events_;
  if (ray >= 0)
    put(fmt::format(R"({{"name":"{}","ph":"X","ts":{},"dur":{},"pid":{},"tid":{},"args":{{"ray":{}}}}})", name, start,
                    end - start, t.pid, t.tid[lane], ray));
  else
    put(fmt::format(R"({{"name":"{}","ph":"X","ts":{},"dur":{},"pid":{},"tid":{}}})", name, start, end - start, t.pid,
                    t.tid[lane]));
}

void TimelineRecorder::put(const std::string& text) {
  if (!first_event_) buffer_ += ",\n";
  first_event_ = false;
  buffer_ += text;
  if (buffer_.size() >= kFlushBytes) flush();
}

void TimelineRecorder::flush() {
  file_->stream().write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  file_->check();
  buffer_.clear();
}

void TimelineRecorder::finish() {
  buffer_ += "\n]}\n";
  flush();
  file_->commit();
}

}  // namespace vbsim::hw
