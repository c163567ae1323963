// Dram: the built-in memory target behind the L2's TLM-2.0 socket, one channel
// (DramChannel: latency, bandwidth, requests in flight; docs/memory-model.md).
// A read of one line arriving at cycle t (SystemC time plus its delay
// annotation, in whole cycles of `clock`) gets its data at
// DramChannel::read_line(t).
//
// Loosely timed: b_transport answers at once, adding the wait to the delay.
// Approximately timed: nb_transport_fw takes BEGIN_REQ (returning END_REQ at
// once) and sends BEGIN_RESP through the backward path when SystemC time
// reaches the data's cycle. Either way requests are served in the order they
// arrive here.
#pragma once
#include <cstdint>

#include <systemc>
#include <tlm>
#include <tlm_utils/peq_with_get.h>

#include "hw/cycle_clock.h"
#include "hw/memory/dram_channel.h"
#include "hw/memory/memory_config.h"
#include "hw/observe/stat_provider.h"
#include "hw/observe/vcd_recorder.h"

namespace vbsim::hw {

class Dram final : public sc_core::sc_module, public tlm::tlm_fw_transport_if<>, public StatProvider {
 public:
  tlm::tlm_target_socket<> socket;

  /// `config`'s dram_* fields are valid (check_memory_config); `clock` outlives the target.
  Dram(sc_core::sc_module_name name, const MemoryConfig& config, const CycleClock& clock);

  void b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) override;
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& trans, tlm::tlm_phase& phase,
                                     sc_core::sc_time& delay) override;
  bool get_direct_mem_ptr(tlm::tlm_generic_payload&, tlm::tlm_dmi&) override { return false; }
  unsigned int transport_dbg(tlm::tlm_generic_payload&) override { return 0; }

  const char* unit_kind() const override { return "Dram"; }
  nlohmann::json parameters() const override;
  const DramChannel& channel() const { return channel_; }
  /// Records its requests in flight and the bytes it has delivered (VCD; null: none).
  void set_tracing(VcdRecorder* vcd);

 private:
  /// The cycle the data of a request arriving `delay` after SystemC time are there.
  uint64_t serve(tlm::tlm_generic_payload& trans, const sc_core::sc_time& delay);
  void respond();  // SC_METHOD: BEGIN_RESP for the responses due now

  MemoryConfig config_;
  const CycleClock& clock_;
  DramChannel channel_;
  tlm_utils::peq_with_get<tlm::tlm_generic_payload> responses_;
  VcdRecorder* vcd_ = nullptr;
  uint32_t vcd_requests_ = VcdRecorder::kNoSignal, vcd_bytes_ = VcdRecorder::kNoSignal;
};

}  // namespace vbsim::hw
