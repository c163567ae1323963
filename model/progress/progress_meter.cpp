#include "progress/progress_meter.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>

namespace vbsim {

namespace {
constexpr std::chrono::milliseconds kRedrawInterval{200};  // callers may report every 250 ms
}

std::string clock_text(double seconds) {
  const uint64_t s = seconds > 0 ? static_cast<uint64_t>(std::ceil(seconds)) : 0;
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
  return fmt::format("{}:{:02}", s / 60, s % 60);
}

std::string progress_text(const std::string& label, uint64_t done, uint64_t total, const std::string& unit,
                          double elapsed_s) {
  if (unit.empty()) return fmt::format("{}  {}", label, clock_text(elapsed_s));  // a step that counts nothing
  const double rate = elapsed_s > 0 ? done / elapsed_s : 0.0;
  if (total == 0) return fmt::format("{}  {} {}  {:.0f} {}/s", label, done, unit, rate, unit);
  std::string s = fmt::format("{}  {:5.1f}%  {}/{} {}  {:.0f} {}/s", label, 100.0 * done / total, done, total,
                              unit, rate, unit);
  if (done > 0 && done < total) s += "  ETA " + clock_text((total - done) / rate);
  return s;
}

ProgressMeter::ProgressMeter(std::string label, uint64_t total, std::string unit, std::FILE* out)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total), out_(out),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

std::FILE* ProgressMeter::terminal_or_null(bool quiet) {
  return !quiet && isatty(STDERR_FILENO) ? stderr : nullptr;
}

void ProgressMeter::update(uint64_t done) {
  done_ = done;
  if (!out_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_draw_ < kRedrawInterval) return;
  draw(now);
}

void ProgressMeter::show() {
  if (out_) draw(std::chrono::steady_clock::now());
}

void ProgressMeter::draw(std::chrono::steady_clock::time_point now) {
  last_draw_ = now;
  const std::string line =
      progress_text(label_, done_, total_, unit_, std::chrono::duration<double>(now - start_).count());
  // Pad with spaces over a longer previous line.
  const size_t pad = last_width_ > line.size() ? last_width_ - line.size() : 0;
  fmt::print(out_, "\r{}{:{}}", line, "", pad);
  std::fflush(out_);
  last_width_ = line.size();
}

void ProgressMeter::finish() {
  if (!out_) return;
  if (last_width_ > 0) fmt::print(out_, "\r{:{}}\r", "", last_width_);
  std::fflush(out_);
  out_ = nullptr;
}

}  // namespace vbsim
