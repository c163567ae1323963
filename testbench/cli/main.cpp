// vbsim command line: subcommands are registered in this file's main().
#include <cstdio>

int main() {
  std::puts("vbsim: no subcommands registered yet");
  return 1;
}
