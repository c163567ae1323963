#include "hw/memory/dram.h"

namespace vbsim::hw {

Dram::Dram(sc_core::sc_module_name name, const MemoryConfig& config, const CycleClock& clock)
    : sc_core::sc_module(name), socket("socket"), config_(config), clock_(clock),
      channel_(dram_line_latency(config), config.dram_bytes_per_cycle, config.l2.line_bytes, config.dram_max_outstanding),
      responses_("responses") {
  socket.bind(*this);
  SC_HAS_PROCESS(Dram);
  SC_METHOD(respond);
  sensitive << responses_.get_event();
  dont_initialize();
  const DramCounters& c = channel_.counters();
  declare_stat("reads", "lines", "line reads served", c.reads);
  declare_stat("bytes", "bytes", "bytes transferred", c.bytes);
  declare_stat("busy_cycles", "cycles", "cycles the channel spent transferring",
               [this] { return channel_.busy_cycles(); });
  declare_stat("outstanding_stall_cycles", "cycles", "cycles requests waited for a free request slot",
               c.outstanding_stall_cycles);
  declare_stat("bandwidth_stall_cycles", "cycles", "cycles requests waited for the channel",
               c.bandwidth_stall_cycles);
}

nlohmann::json Dram::parameters() const {
  return {{"latency", config_.dram_latency},
          {"latency_per_byte", config_.dram_latency_per_byte},
          {"line_latency", dram_line_latency(config_)},
          {"bytes_per_cycle", config_.dram_bytes_per_cycle},
          {"max_outstanding", config_.dram_max_outstanding},
          {"line_bytes", config_.l2.line_bytes}};
}

void Dram::set_tracing(VcdRecorder* vcd) {
  vcd_requests_ = vcd ? vcd->signal(name(), "requests_in_flight") : VcdRecorder::kNoSignal;
  vcd_bytes_ = vcd ? vcd->signal(name(), "bytes") : VcdRecorder::kNoSignal;
  vcd_ = vcd_requests_ == VcdRecorder::kNoSignal ? nullptr : vcd;
}

uint64_t Dram::serve(tlm::tlm_generic_payload& trans, const sc_core::sc_time& delay) {
  const uint64_t arrival = clock_.cycle_after(delay);
  const uint64_t ready = channel_.read_line(arrival);
  if (vcd_) {
    vcd_->add(vcd_requests_, arrival, +1);
    vcd_->add(vcd_requests_, ready, -1);
    vcd_->add(vcd_bytes_, ready, config_.l2.line_bytes);
  }
  trans.set_response_status(trans.get_command() == tlm::TLM_READ_COMMAND ? tlm::TLM_OK_RESPONSE
                                                                          : tlm::TLM_COMMAND_ERROR_RESPONSE);
  return ready;
}

void Dram::b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) {
  delay = clock_.delay_to(serve(trans, delay));
}

tlm::tlm_sync_enum Dram::nb_transport_fw(tlm::tlm_generic_payload& trans, tlm::tlm_phase& phase,
                                         sc_core::sc_time& delay) {
  if (phase == tlm::BEGIN_REQ) {
    trans.acquire();
    responses_.notify(trans, clock_.delay_to(serve(trans, delay)));
    phase = tlm::END_REQ;  // accepted at once; the response follows at its cycle
    return tlm::TLM_UPDATED;
  }
  return tlm::TLM_COMPLETED;  // END_RESP
}

void Dram::respond() {
  while (tlm::tlm_generic_payload* trans = responses_.get_next_transaction()) {
    tlm::tlm_phase phase = tlm::BEGIN_RESP;
    sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
    socket->nb_transport_bw(*trans, phase, delay);  // the initiator completes it (or sends END_RESP later)
    trans->release();
  }
}

}  // namespace vbsim::hw
