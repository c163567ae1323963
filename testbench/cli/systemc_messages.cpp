#include "systemc_messages.h"

#include <cstdio>
#include <systemc>

namespace vbsim::cli {

namespace {

bool g_quiet = false;

void handle_report(const sc_core::sc_report& report, const sc_core::sc_actions& actions) {
  sc_core::sc_actions rest = actions;
  if (actions & sc_core::SC_DISPLAY) {
    rest &= ~static_cast<sc_core::sc_actions>(sc_core::SC_DISPLAY);
    const bool minor = report.get_severity() <= sc_core::SC_WARNING;
    if (!(g_quiet && minor))
      std::fprintf(stderr, "%s\n", sc_core::sc_report_compose_message(report).c_str());
  }
  sc_core::sc_report_handler::default_handler(report, rest);  // log, throw, stop, abort
}

}  // namespace

void route_systemc_messages_to_stderr() { sc_core::sc_report_handler::set_handler(handle_report); }

void set_systemc_quiet(bool quiet) { g_quiet = quiet; }

}  // namespace vbsim::cli
