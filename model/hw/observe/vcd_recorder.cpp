#include "hw/observe/vcd_recorder.h"

#include "io/atomic_output_file.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <stdexcept>

namespace vbsim::hw {

namespace {

/// The VCD identifier of signal `i`: printable characters '!'..'~' as digits.
std::string vcd_id(uint32_t i) {
  std::string s;
  do {
    s += static_cast<char>('!' + i % 94);
    i /= 94;
  } while (i);
  return s;
}

std::string binary(int64_t v) {
  if (v <= 0) return "0";  // levels are counts (a negative one would be a model error)
  std::string s;
  for (uint64_t u = static_cast<uint64_t>(v); u; u >>= 1) s += static_cast<char>('0' + (u & 1));
  std::reverse(s.begin(), s.end());
  return s;
}

/// The instance path split at dots.
std::vector<std::string> scopes_of(const std::string& instance) {
  std::vector<std::string> out;
  size_t at = 0;
  for (;;) {
    const size_t dot = instance.find('.', at);
    out.push_back(instance.substr(at, dot == std::string::npos ? std::string::npos : dot - at));
    if (dot == std::string::npos) return out;
    at = dot + 1;
  }
}

}  // namespace

VcdRecorder::VcdRecorder(uint64_t first, uint64_t cycles, uint64_t period_ps, TraceScope scope, size_t spill_chunk)
    : first_(first), end_(first + cycles < first ? ~uint64_t{0} : first + cycles), period_ps_(period_ps),
      scope_(std::move(scope)), changes_(spill_chunk) {}

uint32_t VcdRecorder::signal(const std::string& instance, const std::string& name) {
  if (!scope_.matches(instance)) return kNoSignal;
  instances_.push_back(instance);
  names_.push_back(name);
  base_.push_back(0);
  return static_cast<uint32_t>(names_.size() - 1);
}

void VcdRecorder::write(const std::string& path, uint64_t run_end) {
  AtomicOutputFile file(path);  // named only once complete; throws OutputError naming the path
  std::ostream& out = file.stream();
  const uint64_t end = std::max(first_, std::min(end_, run_end + 1));  // [first, end): the run's last cycle included
  out << "$comment vbsim cycle-level model, cycles " << first_ << " to " << end << " $end\n";
  out << "$timescale 1 ps $end\n";
  // Signals grouped by instance, scopes nested by the dotted name.
  std::map<std::string, std::vector<uint32_t>> by_instance;
  for (uint32_t i = 0; i < names_.size(); ++i) by_instance[instances_[i]].push_back(i);
  std::vector<std::string> open;
  for (const auto& [instance, ids] : by_instance) {
    const std::vector<std::string> want = scopes_of(instance);
    size_t common = 0;
    while (common < open.size() && common < want.size() && open[common] == want[common]) ++common;
    while (open.size() > common) {
      out << "$upscope $end\n";
      open.pop_back();
    }
    for (size_t k = common; k < want.size(); ++k) {
      out << "$scope module " << want[k] << " $end\n";
      open.push_back(want[k]);
    }
    for (const uint32_t id : ids) out << "$var integer 32 " << vcd_id(id) << " " << names_[id] << " $end\n";
  }
  while (!open.empty()) {
    out << "$upscope $end\n";
    open.pop_back();
  }
  out << "$enddefinitions $end\n";

  std::vector<int64_t> level = base_;
  out << "#" << first_ * period_ps_ << "\n$dumpvars\n";
  for (uint32_t i = 0; i < level.size(); ++i) out << "b" << binary(level[i]) << " " << vcd_id(i) << "\n";
  out << "$end\n";
  VcdChangeLog::Change c{};
  for (bool have = changes_.next(c); have;) {
    const uint64_t cycle = c.cycle;
    if (cycle >= end) break;
    std::map<uint32_t, int64_t> touched;
    for (; have && c.cycle == cycle; have = changes_.next(c)) {
      touched.emplace(c.id, level[c.id]);
      level[c.id] += c.delta;
    }
    bool any = false;
    for (const auto& [id, old] : touched) any |= level[id] != old;
    if (!any) continue;
    if (cycle > first_) out << "#" << cycle * period_ps_ << "\n";
    for (const auto& [id, old] : touched)
      if (level[id] != old) out << "b" << binary(level[id]) << " " << vcd_id(id) << "\n";
  }
  out << "#" << end * period_ps_ << "\n";
  file.commit();
}

}  // namespace vbsim::hw
