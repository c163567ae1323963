// BankedMemory: a memory target written for the tests, in approximately timed
// style, whose latency depends on its state, as a DRAM controller's does. It
// binds to the accelerator's memory socket in place of the built-in Dram.
//
// Line l (byte address / line_bytes) lives in bank l % banks, row
// l / (banks * lines_per_row). A read arriving at cycle t (its BEGIN_REQ time,
// delay annotation included) is accepted one cycle later (END_REQ on the
// backward path: the next request waits for it, the base protocol's request
// exclusion), and its bank serves it from s = max(t, the bank's previous
// ready cycle): ready = s + row_hit if the bank's open row is the line's, else
// s + row_miss; the row stays open. BEGIN_RESP goes back at the ready cycle.
// Requests are taken in the order they arrive (payload event queues).
#pragma once
#include <cstdint>
#include <vector>

#include <systemc>
#include <tlm>
#include <tlm_utils/peq_with_get.h>

namespace vbsim::hw::test {

struct BankedMemoryConfig {
  uint32_t banks = 2, lines_per_row = 4, line_bytes = 64;
  uint32_t row_hit = 12, row_miss = 40;  ///< cycles from service start to data
};

class BankedMemory final : public sc_core::sc_module, public tlm::tlm_fw_transport_if<> {
 public:
  tlm::tlm_target_socket<> socket;
  uint64_t row_hits = 0, row_misses = 0;

  BankedMemory(sc_core::sc_module_name name, const BankedMemoryConfig& c, const sc_core::sc_time& period)
      : sc_core::sc_module(name), socket("socket"), c_(c), period_(period), free_(c.banks, 0),
        open_row_(c.banks, ~uint64_t{0}), arrivals_("arrivals"), accepts_("accepts"), responses_("responses") {
    socket.bind(*this);
    SC_HAS_PROCESS(BankedMemory);
    SC_METHOD(on_arrival);
    sensitive << arrivals_.get_event();
    dont_initialize();
    SC_METHOD(on_accept);
    sensitive << accepts_.get_event();
    dont_initialize();
    SC_METHOD(on_response);
    sensitive << responses_.get_event();
    dont_initialize();
  }

  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& trans, tlm::tlm_phase& phase,
                                     sc_core::sc_time& delay) override {
    if (phase != tlm::BEGIN_REQ) return tlm::TLM_COMPLETED;  // END_RESP
    trans.acquire();
    arrivals_.notify(trans, delay);
    return tlm::TLM_ACCEPTED;
  }
  void b_transport(tlm::tlm_generic_payload&, sc_core::sc_time&) override {
    SC_REPORT_ERROR("BankedMemory", "approximately timed only");
  }
  bool get_direct_mem_ptr(tlm::tlm_generic_payload&, tlm::tlm_dmi&) override { return false; }
  unsigned int transport_dbg(tlm::tlm_generic_payload&) override { return 0; }

 private:
  uint64_t cycle_now() const { return sc_core::sc_time_stamp().value() / period_.value(); }
  sc_core::sc_time cycles(uint64_t n) const { return sc_core::sc_time::from_value(period_.value() * n); }

  void on_arrival() {
    while (tlm::tlm_generic_payload* t = arrivals_.get_next_transaction()) {
      const uint64_t now = cycle_now(), line = t->get_address() / c_.line_bytes;
      const uint32_t bank = static_cast<uint32_t>(line % c_.banks);
      const uint64_t row = line / (uint64_t{c_.banks} * c_.lines_per_row);
      const uint64_t start = std::max(now, free_[bank]);
      const bool hit = open_row_[bank] == row;
      (hit ? row_hits : row_misses)++;
      const uint64_t ready = start + (hit ? c_.row_hit : c_.row_miss);
      free_[bank] = ready;
      open_row_[bank] = row;
      t->set_response_status(tlm::TLM_OK_RESPONSE);
      accepts_.notify(*t, cycles(1));
      responses_.notify(*t, cycles(ready - now));
    }
  }
  void on_accept() {
    while (tlm::tlm_generic_payload* t = accepts_.get_next_transaction()) {
      tlm::tlm_phase phase = tlm::END_REQ;
      sc_core::sc_time zero = sc_core::SC_ZERO_TIME;
      socket->nb_transport_bw(*t, phase, zero);
    }
  }
  void on_response() {
    while (tlm::tlm_generic_payload* t = responses_.get_next_transaction()) {
      tlm::tlm_phase phase = tlm::BEGIN_RESP;
      sc_core::sc_time zero = sc_core::SC_ZERO_TIME;
      socket->nb_transport_bw(*t, phase, zero);
      t->release();
    }
  }

  BankedMemoryConfig c_;
  sc_core::sc_time period_;
  std::vector<uint64_t> free_, open_row_;
  tlm_utils::peq_with_get<tlm::tlm_generic_payload> arrivals_, accepts_, responses_;
};

}  // namespace vbsim::hw::test
