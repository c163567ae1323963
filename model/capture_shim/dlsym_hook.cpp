// The shim's dlsym: an application that dlopens libembree3 itself and looks
// its functions up with dlsym(handle, "rtc...") gets the shim's definitions
// (embree_entry_for), so that its calls are captured like those of a program
// linked to Embree; a lookup in a library that dlmopen loaded into a namespace
// holding Embree refuses the capture (check_handle_namespace) before the
// application can trace there. Every other lookup is the C library's own.
//
// The C library's dlsym resolves RTLD_NEXT (and RTLD_DEFAULT) relative to the
// object that called it, found from its return address. So those two are
// passed on with a jump, never a call: the C library then sees the
// application's return address, and RTLD_NEXT means what it means without the
// shim. On x86-64 the entry point is written in assembly so that this holds at
// every optimisation level; elsewhere the compiler's tail call is relied on.
#include <dlfcn.h>

#include <cstdio>
#include <cstring>
#include <unistd.h>

#include "capture_output.h"
#include "embree_library.h"

using Dlsym = void* (*)(void*, const char*);

extern "C" {

/// The C library's dlsym, once found (vbsim_find_real_dlsym).
__attribute__((visibility("hidden"))) Dlsym vbsim_real_dlsym = nullptr;

/// Finds the C library's dlsym by version (dlvsym is not interposed); never returns null.
__attribute__((visibility("hidden"))) Dlsym vbsim_find_real_dlsym() {
  // glibc 2.34 moved dlsym into libc (GLIBC_2.34); before, the architecture's first version.
  for (const char* version : {"GLIBC_2.34", "GLIBC_2.2.5", "GLIBC_2.17", "GLIBC_2.0", "GLIBC_2.1"})
    if (void* f = dlvsym(RTLD_NEXT, "dlsym", version)) return vbsim_real_dlsym = reinterpret_cast<Dlsym>(f);
  static const char kMessage[] = "vbsim capture shim: the C library's dlsym was not found\n";
  (void)!::write(2, kMessage, sizeof kMessage - 1);
  ::_exit(vbsim::capture::kShimRefusedStatus);
}

/// dlsym(handle, name) for a library handle: an Embree function the shim interposes is the shim's.
__attribute__((visibility("hidden"))) void* vbsim_dlsym_in_handle(void* handle, const char* name) {
  void* found = vbsim_real_dlsym(handle, name);
  if (!found) return found;
  vbsim::shim::check_handle_namespace(handle);
  if (!name || std::strncmp(name, "rtc", 3) != 0) return found;
  return vbsim::shim::embree_entry_for(name, found);
}

}  // extern "C"

#if defined(__x86_64__)
// dlsym(rdi = handle, rsi = name): RTLD_NEXT (-1) and RTLD_DEFAULT (0) jump to
// the C library's dlsym, any other handle to vbsim_dlsym_in_handle.
asm(R"(
  .text
  .globl dlsym
  .type dlsym, @function
dlsym:
  .cfi_startproc
)"
#if defined(__CET__)
    "  endbr64\n"
#endif
    R"(
1:
  movq vbsim_real_dlsym(%rip), %rax
  testq %rax, %rax
  jz 3f
  cmpq $-1, %rdi
  je 2f
  testq %rdi, %rdi
  je 2f
  jmp vbsim_dlsym_in_handle
2:
  jmp *%rax
3:
  pushq %rdi
  .cfi_adjust_cfa_offset 8
  pushq %rsi
  .cfi_adjust_cfa_offset 8
  subq $8, %rsp
  .cfi_adjust_cfa_offset 8
  call vbsim_find_real_dlsym
  addq $8, %rsp
  .cfi_adjust_cfa_offset -8
  popq %rsi
  .cfi_adjust_cfa_offset -8
  popq %rdi
  .cfi_adjust_cfa_offset -8
  jmp 1b
  .cfi_endproc
  .size dlsym, .-dlsym
)");
#else
extern "C" __attribute__((optimize("O2"))) void* dlsym(void* handle, const char* name) noexcept {
  const Dlsym real = vbsim_real_dlsym ? vbsim_real_dlsym : vbsim_find_real_dlsym();
  if (handle == RTLD_NEXT || handle == RTLD_DEFAULT) return real(handle, name);  // a tail call
  return vbsim_dlsym_in_handle(handle, name);
}
#endif

namespace vbsim::shim {

void* real_dlsym(void* handle, const char* name) {
  const Dlsym real = vbsim_real_dlsym ? vbsim_real_dlsym : vbsim_find_real_dlsym();
  return real(handle, name);
}

}  // namespace vbsim::shim
