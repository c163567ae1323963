// Entry point of the Catch2 test binary. Kept as an explicit Catch::Session so
// that the SystemC module tests can later run it from sc_main.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

int main(int argc, char* argv[]) { return Catch::Session().run(argc, argv); }
