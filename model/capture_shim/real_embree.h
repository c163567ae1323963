// The application's Embree functions behind the shim's interposed ones: each
// is looked up once with dlsym(RTLD_NEXT), i.e. in the libraries loaded after
// the preloaded shim (libembree3). The shim calls nothing else of Embree.
#pragma once
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>

#include <embree3/rtcore.h>

namespace vbsim::shim {

/// The next definition of `name` (a function of type F) after the shim's own.
template <class F>
F next_definition(const char* name) {
  void* f = dlsym(RTLD_NEXT, name);
  if (!f) {
    std::fprintf(stderr, "vbsim capture shim: %s not found after the shim (is the application linked to Embree 3?)\n",
                 name);
    std::abort();
  }
  return reinterpret_cast<F>(f);
}

}  // namespace vbsim::shim

/// Declares `real` as the application's own `name`, resolved on first use.
#define VBSIM_REAL(name) \
  static const auto real = ::vbsim::shim::next_definition<decltype(&::name)>(#name)
