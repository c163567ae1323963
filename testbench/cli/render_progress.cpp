#include "render_progress.h"

#include <fmt/format.h>

namespace vbsim::cli {

RenderProgress::RenderProgress(uint64_t pixels, bool quiet)
    : pixels_(pixels),
      quiet_(quiet),
      meter_("render", pixels, "pixels", ProgressMeter::terminal_or_null(quiet)),
      start_(std::chrono::steady_clock::now()),
      window_start_(start_) {}

void RenderProgress::update(uint64_t finished) {
  meter_.update(finished);
  if (warned_ || quiet_ || finished <= window_pixels_ || finished >= pixels_) return;
  const auto now = std::chrono::steady_clock::now();
  const double window = std::chrono::duration<double>(now - window_start_).count();
  if (window < kSlowRenderJudgeSeconds) return;
  // The pace of the pixels of the last window, not of the whole frame so far:
  // a frame whose first rows miss everything is fast until its rays reach the
  // slow geometry, and then the average lags far behind.
  const uint64_t done_in_window = finished - window_pixels_;
  const double per_pixel = window / static_cast<double>(done_in_window);
  const double left = per_pixel * static_cast<double>(pixels_ - finished);
  window_start_ = now;
  window_pixels_ = finished;
  if (left <= kSlowRenderWarnSeconds) return;
  warned_ = true;
  if (meter_.shown()) std::fputc('\n', stderr);  // below the progress line, which goes on
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  fmt::print(stderr,
             "vbsim render: warning: a slow frame: {} of {} pixels in {:.1f} s, the last {} at {:.3g} s a pixel: "
             "about {} left at that pace. Rays that each meet many triangles (stacked or overlapping geometry) are "
             "slow; a smaller --size renders sooner\n",
             finished, pixels_, elapsed, done_in_window, per_pixel, clock_text(left));
  std::fflush(stderr);
}

}  // namespace vbsim::cli
