// Where the application's Embree 3 is, however it was loaded: linked by the
// program (found after the shim, dlsym RTLD_NEXT) or loaded with dlopen as a
// local library (RTLD_LOCAL: not in the global scope, so found among the
// loaded objects by name, libembree3.*, in the program's link-map namespace).
// What cannot be captured is refused with a reason (refuse_capture): Embree 4
// (another API under the same names), or a libembree3 that dlmopen loaded into
// a namespace of its own, where the preloaded shim is not.
#pragma once
#include <string>

namespace vbsim::shim {

/// The C library's `name` after the shim's own (dlsym RTLD_NEXT); never null
/// (refuses the capture when there is none).
void* next_function(const char* name);

/// The application's Embree 3 function `name`: the definition after the shim,
/// else the one in a libembree3 loaded locally in the program's namespace.
/// Never null: without one, or when it is Embree 4's, refuses the capture.
void* embree_function(const char* name);

/// True when a libembree3 is loaded in the program's namespace (either way).
bool embree_loaded();

/// Empty, or why an Embree loaded into this process is out of the shim's
/// reach (a copy of libembree3 or libembree4 in another link-map namespace).
std::string embree_out_of_reach();

/// Before the application uses a library `handle` it looked a symbol up in:
/// refuses the capture when the handle is in another link-map namespace
/// (dlmopen) that holds a libembree3 or libembree4, since nothing traced
/// there reaches the shim.
void check_handle_namespace(void* handle);

/// What dlsym(handle, name) gives the application for an Embree function
/// `found` in a library: the shim's own definition of `name` when the shim
/// interposes it (so that calls through the pointer are captured), else `found`.
void* embree_entry_for(const char* name, void* found);

/// The C library's dlsym, for the shim's own lookups in a library handle
/// (the shim's dlsym passes such lookups through embree_entry_for).
void* real_dlsym(void* handle, const char* name);

}  // namespace vbsim::shim
