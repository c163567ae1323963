// WorkProgress: how far a long step without rays has come (reading a scene,
// checking it, building its BVH), for a display. The scene loader and the BVH
// builder report through one when given it; a null pointer reports nowhere.
// Reporters are told at most every megabyte or so, never per item, and only
// from the thread that runs the step.
#pragma once
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

#include "progress/progress_meter.h"

namespace vbsim {

class WorkProgress {
 public:
  virtual ~WorkProgress() = default;
  /// A new step begins: `total` `unit` to do (0: unknown; only the step is shown).
  virtual void begin(const std::string& step, uint64_t total, const std::string& unit) = 0;
  /// `done` of the current step's total are done.
  virtual void update(uint64_t done) = 0;
};

/// One ProgressMeter line a step, "LABEL: STEP  43.2%  371/858 MB ...", on
/// `out` (ProgressMeter::terminal_or_null: a terminal unless quiet); null
/// draws nothing. The line is cleared when the next step begins and at finish().
class MeterWorkProgress final : public WorkProgress {
 public:
  MeterWorkProgress(std::string label, std::FILE* out) : label_(std::move(label)), out_(out) {}
  ~MeterWorkProgress() override { finish(); }
  void begin(const std::string& step, uint64_t total, const std::string& unit) override;
  void update(uint64_t done) override;
  void finish();

 private:
  std::string label_;
  std::FILE* out_;
  std::unique_ptr<ProgressMeter> meter_;
};

/// Bytes as whole megabytes (10^6, rounded up) for a step counted in "MB".
inline uint64_t megabytes(uint64_t bytes) { return (bytes + 999999) / 1000000; }

}  // namespace vbsim
