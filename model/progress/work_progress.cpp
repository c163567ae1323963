#include "progress/work_progress.h"

namespace vbsim {

void MeterWorkProgress::begin(const std::string& step, uint64_t total, const std::string& unit) {
  finish();
  if (out_ == nullptr) return;
  meter_ = std::make_unique<ProgressMeter>(label_ + ": " + step, total, unit, out_);
  meter_->show();
}

void MeterWorkProgress::update(uint64_t done) {
  if (meter_) meter_->update(done);
}

void MeterWorkProgress::finish() {
  if (meter_) meter_->finish();
  meter_.reset();
}

}  // namespace vbsim
