// RecordingMemory: a memory target written for the tests, in either TLM-2.0
// style: every line `latency` cycles after its request arrives (SystemC time
// plus the delay annotation), recording the arrival cycles in the order the
// requests reach it. It binds to the accelerator's memory socket in place of
// the built-in Dram.
#pragma once
#include <cstdint>
#include <vector>

#include <systemc>
#include <tlm>
#include <tlm_utils/peq_with_get.h>

namespace vbsim::hw::test {

class RecordingMemory final : public sc_core::sc_module, public tlm::tlm_fw_transport_if<> {
 public:
  tlm::tlm_target_socket<> socket;
  std::vector<uint64_t> arrivals;

  RecordingMemory(sc_core::sc_module_name n, const sc_core::sc_time& period, uint64_t latency)
      : sc_core::sc_module(n), socket("socket"), period_(period), latency_(latency), responses_("responses") {
    socket.bind(*this);
    SC_HAS_PROCESS(RecordingMemory);
    SC_METHOD(respond);
    sensitive << responses_.get_event();
    dont_initialize();
  }
  void b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) override {
    arrive(delay);
    delay += period_ * static_cast<double>(latency_);
    trans.set_response_status(tlm::TLM_OK_RESPONSE);
  }
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& trans, tlm::tlm_phase& phase,
                                     sc_core::sc_time& delay) override {
    if (phase != tlm::BEGIN_REQ) return tlm::TLM_COMPLETED;
    arrive(delay);
    trans.acquire();
    trans.set_response_status(tlm::TLM_OK_RESPONSE);
    responses_.notify(trans, delay + period_ * static_cast<double>(latency_));
    phase = tlm::END_REQ;
    return tlm::TLM_UPDATED;
  }
  bool get_direct_mem_ptr(tlm::tlm_generic_payload&, tlm::tlm_dmi&) override { return false; }
  unsigned int transport_dbg(tlm::tlm_generic_payload&) override { return 0; }

 private:
  void arrive(const sc_core::sc_time& delay) {
    arrivals.push_back(static_cast<uint64_t>((sc_core::sc_time_stamp() + delay).value() / period_.value()));
  }
  void respond() {
    while (tlm::tlm_generic_payload* t = responses_.get_next_transaction()) {
      tlm::tlm_phase phase = tlm::BEGIN_RESP;
      sc_core::sc_time zero = sc_core::SC_ZERO_TIME;
      socket->nb_transport_bw(*t, phase, zero);
      t->release();
    }
  }
  sc_core::sc_time period_;
  uint64_t latency_;
  tlm_utils::peq_with_get<tlm::tlm_generic_payload> responses_;
};

}  // namespace vbsim::hw::test
