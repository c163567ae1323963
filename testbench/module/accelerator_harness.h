// A test bench around one Accelerator: its own simulation context, a list of
// rays, a memory target of the test's own bound to the memory socket when it
// brings one, and each ray's answer and finish cycle.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <vector>

#include <systemc>

#include "hw/accelerator.h"
#include "hw/simulation_context.h"

namespace vbsim::hw::test {

struct Finished {
  int32_t prim;
  uint64_t cycle;
};

class AcceleratorHarness {
 public:
  /// `attach` (may be empty) builds and binds the test's own module (e.g. a
  /// memory target on acc.memory_socket()) before the simulation starts; the
  /// harness keeps it.
  using Attach = std::function<std::unique_ptr<sc_core::sc_module>(Accelerator&)>;
  AcceleratorHarness(const Scene& scene, const Bvh& bvh, const HwConfig& cfg, const ReplayOptions& opt,
                     const AcceleratorUnits& units = {}, const Attach& attach = {}) {
    acc_ = std::make_unique<Accelerator>("accelerator", cfg, scene, bvh, opt, units);
    if (attach) attached_ = attach(*acc_);
  }
  ~AcceleratorHarness() {
    acc_.reset();
    attached_.reset();
  }

  /// The module `attach` made, as `M` (null when it is not one).
  template <class M>
  M* attached() const {
    return dynamic_cast<M*>(attached_.get());
  }

  /// Replays `rays` to the end (Accelerator::check() included).
  void run(const std::vector<TraceRay>& rays) {
    size_t next = 0;
    acc_->set_feed([rays, next](TraceRay& tr) mutable {
      if (next == rays.size()) return false;
      tr = rays[next++];
      return true;
    });
    acc_->set_track_parents(false);
    acc_->set_result_callback([this](const TraceRay& tr, const RayOutcome& out, uint64_t cycle, uint64_t) {
      finished[tr.id] = {out.hit.prim, cycle};
    });
    sc_core::sc_start();
    acc_->check();
  }

  Accelerator& accelerator() { return *acc_; }
  std::map<int64_t, Finished> finished;

 private:
  SimulationContext context_;  // first member: destroyed last
  std::unique_ptr<sc_core::sc_module> attached_;
  std::unique_ptr<Accelerator> acc_;
};

}  // namespace vbsim::hw::test
