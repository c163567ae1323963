// Entry point of the Catch2 test binary. libsystemc.so brings a main() that
// calls sc_main(); this binary defines its own main() (which the linker
// prefers) only to silence SystemC's banner before handing over to SystemC,
// and runs Catch::Session from sc_main, so SystemC tests run inside a normal
// SystemC context.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdlib>
#include <systemc>

int sc_main(int argc, char* argv[]) { return Catch::Session().run(argc, argv); }

int main(int argc, char* argv[]) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 0);
  return sc_core::sc_elab_and_sim(argc, argv);
}
