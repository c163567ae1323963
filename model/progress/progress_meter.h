// A one-line progress display on a terminal: done/total, percentage, rate and
// estimated time left, rewritten in place on stderr at most four times a second.
// Commands create one only when stderr is a terminal and -q is not given, so
// logs, pipes and scripts see nothing of it.
#pragma once
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>

namespace vbsim {

/// The line for `done` of `total` `unit` after `elapsed_s` seconds, e.g.
/// "replay  43.2%  432100/1000000 rays  86420 rays/s  ETA 0:07". `total` 0 is
/// unknown: count and rate only. The ETA is (total - done) / (done / elapsed),
/// shown once something is done; h:mm:ss from an hour up, else m:ss. An empty
/// `unit` counts nothing: the label and the time elapsed only.
std::string progress_text(const std::string& label, uint64_t done, uint64_t total, const std::string& unit,
                          double elapsed_s);

/// "m:ss" or "h:mm:ss" of a non-negative number of seconds (rounded up).
std::string clock_text(double seconds);

class ProgressMeter {
 public:
  /// A meter writing to `out`; a null `out` makes every call a no-op.
  ProgressMeter(std::string label, uint64_t total, std::string unit, std::FILE* out);
  ~ProgressMeter() { finish(); }
  ProgressMeter(const ProgressMeter&) = delete;
  ProgressMeter& operator=(const ProgressMeter&) = delete;

  /// stderr when it is a terminal and `quiet` is false, else null.
  static std::FILE* terminal_or_null(bool quiet);

  /// Sets the count done and redraws when a quarter second has passed.
  void update(uint64_t done);
  /// Draws the line now, whatever the time since the last drawing.
  void show();
  /// Adds to the count done.
  void add(uint64_t n) { update(done_ + n); }
  void set_total(uint64_t total) { total_ = total; }
  /// Clears the line (once); later calls do nothing.
  void finish();
  bool shown() const { return out_ != nullptr; }

 private:
  void draw(std::chrono::steady_clock::time_point now);
  std::string label_, unit_;
  uint64_t total_ = 0, done_ = 0;
  std::FILE* out_;
  size_t last_width_ = 0;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace vbsim
