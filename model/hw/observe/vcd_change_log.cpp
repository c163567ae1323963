#include "hw/observe/vcd_change_log.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace vbsim::hw {

namespace {
constexpr size_t kReadBatch = 4096;  // changes read from a spilled run at a time
bool by_cycle(const VcdChangeLog::Change& a, const VcdChangeLog::Change& b) { return a.cycle < b.cycle; }
}  // namespace

VcdChangeLog::~VcdChangeLog() {
  if (file_) std::fclose(file_);
}

void VcdChangeLog::spill() {
  std::sort(buffer_.begin(), buffer_.end(), by_cycle);
  if (!file_ && !(file_ = std::tmpfile()))
    throw std::runtime_error(std::string("VCD: cannot create a temporary file for its changes: ") + std::strerror(errno));
  if (std::fseek(file_, 0, SEEK_END) != 0) throw std::runtime_error("VCD: cannot seek in its temporary file");
  const long offset = std::ftell(file_);
  if (std::fwrite(buffer_.data(), sizeof(Change), buffer_.size(), file_) != buffer_.size())
    throw std::runtime_error(std::string("VCD: cannot write its temporary file: ") + std::strerror(errno));
  runs_.push_back({offset, buffer_.size(), {}, 0});
  buffer_.clear();
}

void VcdChangeLog::finish_adding() {
  if (reading_) return;
  reading_ = true;
  if (!runs_.empty() && !buffer_.empty()) spill();  // every run from the file
  if (runs_.empty()) {  // all in memory: one run, already there
    std::sort(buffer_.begin(), buffer_.end(), by_cycle);
    runs_.push_back({0, 0, std::move(buffer_), 0});
  } else {
    for (Run& r : runs_) refill(r);
  }
  const auto later = [this](uint32_t a, uint32_t b) {
    return runs_[a].buffer[runs_[a].at].cycle > runs_[b].buffer[runs_[b].at].cycle;
  };
  for (uint32_t i = 0; i < runs_.size(); ++i)
    if (runs_[i].at < runs_[i].buffer.size()) heap_.push_back(i);
  std::make_heap(heap_.begin(), heap_.end(), later);
}

bool VcdChangeLog::refill(Run& r) {
  r.buffer.resize(std::min(r.left, kReadBatch));
  r.at = 0;
  if (r.buffer.empty()) return false;
  if (std::fseek(file_, r.offset, SEEK_SET) != 0 ||
      std::fread(r.buffer.data(), sizeof(Change), r.buffer.size(), file_) != r.buffer.size())
    throw std::runtime_error("VCD: cannot read its temporary file back");
  r.offset += static_cast<long>(r.buffer.size() * sizeof(Change));
  r.left -= r.buffer.size();
  return true;
}

bool VcdChangeLog::next(Change& c) {
  if (!reading_) finish_adding();
  if (heap_.empty()) return false;
  const auto later = [this](uint32_t a, uint32_t b) {
    return runs_[a].buffer[runs_[a].at].cycle > runs_[b].buffer[runs_[b].at].cycle;
  };
  std::pop_heap(heap_.begin(), heap_.end(), later);
  Run& r = runs_[heap_.back()];
  c = r.buffer[r.at++];
  if (r.at < r.buffer.size() || refill(r)) std::push_heap(heap_.begin(), heap_.end(), later);
  else heap_.pop_back();
  return true;
}

}  // namespace vbsim::hw
