#include "trace/text_line_block.h"

#include <algorithm>

#include "parallel/parallel_for.h"
#include "trace/text_ray_parse.h"

namespace vbsim {

namespace {

/// Lines a thread takes at a time.
constexpr std::size_t kLinesPerJob = 32;

}  // namespace

std::string& TextLineBlock::free_line() {
  if (count_ == lines_.size()) {
    lines_.emplace_back();
    numbers_.push_back(0);
    rays_.emplace_back();
    errors_.emplace_back();
  }
  return lines_[count_];
}

void TextLineBlock::commit(int64_t line_number) { numbers_[count_++] = line_number; }

void TextLineBlock::parse(int threads) {
  parallel_for_chunks(count_, kLinesPerJob, threads, [this](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      errors_[i] = nullptr;
      try {
        parse_trace_ray_line(lines_[i], rays_[i]);
      } catch (...) {  // thrown again when the reader reaches the line
        errors_[i] = std::current_exception();
      }
    }
  });
}

void TextLineBlock::take(std::size_t i, TraceRay& out) const {
  if (errors_[i]) std::rethrow_exception(errors_[i]);
  out = rays_[i];
}

}  // namespace vbsim
