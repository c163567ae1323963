// What a render shows while it runs. On a terminal: the progress line every
// long command keeps (README "Progress": pixels done, rate, time left). On any
// stderr: one warning as soon as the pixels finished so far show that the
// frame will take long, with the pace and the time left, so that a slow frame
// (a scene whose rays each meet many triangles, such as stacked coplanar ones,
// renders at a tenth of a second a pixel and more) does not look hung. The
// pace is that of the pixels finished in the last two seconds, judged every
// two seconds until it warns (a frame whose first rows miss everything is
// fast until its rays reach the slow geometry). Nothing with -q.
#pragma once
#include <chrono>
#include <cstdint>
#include <cstdio>

#include "progress/progress_meter.h"

namespace vbsim::cli {

/// The pace is judged over windows of this many seconds (at the first pixel
/// finished after each window's end)...
constexpr double kSlowRenderJudgeSeconds = 2.0;
/// ...and a frame whose time left at that pace is beyond this many seconds is warned of.
constexpr double kSlowRenderWarnSeconds = 60.0;

class RenderProgress {
 public:
  /// `pixels` of the frame; `quiet` (-q): nothing is shown.
  RenderProgress(uint64_t pixels, bool quiet);
  /// After each pixel: `finished` pixels so far.
  void update(uint64_t finished);
  /// Clears the progress line.
  void finish() { meter_.finish(); }
  bool warned() const { return warned_; }

 private:
  uint64_t pixels_;
  bool quiet_;
  bool warned_ = false;
  ProgressMeter meter_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point window_start_;  ///< the current window's start...
  uint64_t window_pixels_ = 0;                          ///< ...and the pixels finished then
};

}  // namespace vbsim::cli
