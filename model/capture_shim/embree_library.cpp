#include "embree_library.h"

#include <dlfcn.h>
#include <link.h>

#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include "capture_output.h"

namespace vbsim::shim {

namespace {

/// A libembree3 or libembree4 mapped into the program's namespace.
struct LoadedEmbree {
  std::string path;
  ElfW(Addr) base = 0;  ///< dl_phdr_info::dlpi_addr
  bool embree4 = false;
};

/// The file name of `path` after its last '/'.
const char* base_name(const char* path) {
  const char* slash = std::strrchr(path, '/');
  return slash ? slash + 1 : path;
}

bool starts_with(const char* s, const char* prefix) { return std::strncmp(s, prefix, std::strlen(prefix)) == 0; }

int collect(dl_phdr_info* info, size_t, void* data) {
  if (!info->dlpi_name || !*info->dlpi_name) return 0;
  const char* name = base_name(info->dlpi_name);
  const bool e3 = starts_with(name, "libembree3."), e4 = starts_with(name, "libembree4.");
  if (e3 || e4) static_cast<std::vector<LoadedEmbree>*>(data)->push_back({info->dlpi_name, info->dlpi_addr, e4});
  return 0;
}

/// Every libembree3 and libembree4 of the shim's namespace (dl_iterate_phdr visits the caller's).
std::vector<LoadedEmbree> loaded_embrees() {
  std::vector<LoadedEmbree> found;
  dl_iterate_phdr(collect, &found);
  return found;
}

/// A handle on `e` when it is loaded in the shim's (the program's) namespace, else null.
void* handle_in_program_namespace(const LoadedEmbree& e) {
  void* h = dlopen(e.path.c_str(), RTLD_NOLOAD | RTLD_LAZY);  // only looks in the caller's namespace
  if (!h) {
    dlerror();  // leave the application no error of the shim's to read
    return nullptr;
  }
  link_map* map = nullptr;
  if (dlinfo(h, RTLD_DI_LINKMAP, &map) != 0 || !map || map->l_addr != e.base) {
    dlclose(h);
    dlerror();
    return nullptr;
  }
  return h;  // kept open: the shim calls into it until the process ends
}

/// The locally loaded libembree3 of the program's namespace (null when none), found once.
void* local_embree3() {
  static std::mutex m;
  static void* handle = nullptr;
  std::lock_guard<std::mutex> lock(m);
  if (!handle)
    for (const LoadedEmbree& e : loaded_embrees())
      if (!e.embree4 && (handle = handle_in_program_namespace(e))) break;
  return handle;
}

/// The file that defines the function at `f`, or "" when unknown.
std::string defining_file(void* f) {
  Dl_info info{};
  return dladdr(f, &info) && info.dli_fname ? info.dli_fname : "";
}

/// The shim's own library handle (for its own definitions of Embree's names).
void* shim_handle() {
  static void* h = [] {
    const std::string self = defining_file(reinterpret_cast<void*>(&embree_function));
    void* s = self.empty() ? nullptr : dlopen(self.c_str(), RTLD_NOLOAD | RTLD_LAZY);
    if (!s) dlerror();
    return s;
  }();
  return h;
}

/// The first libembree3 or libembree4 among the objects of the namespace whose first object is `first`, or "".
std::string embree_in_namespace(const link_map* first) {
  for (const link_map* l = first; l; l = l->l_next) {
    if (!l->l_name || !*l->l_name) continue;
    const char* name = base_name(l->l_name);
    if (starts_with(name, "libembree3.") || starts_with(name, "libembree4.")) return l->l_name;
  }
  return "";
}

std::string out_of_namespace_reason(const std::string& path) {
  return path + " is loaded (dlmopen) in a link-map namespace of its own, where the preloaded capture shim is "
         "not: the ray queries traced through it cannot be captured";
}

}  // namespace

void* next_function(const char* name) {
  if (void* f = dlsym(RTLD_NEXT, name)) return f;
  refuse_capture(std::string("the C library's ") + name + " was not found after the capture shim");
}

void* embree_function(const char* name) {
  void* f = dlsym(RTLD_NEXT, name);  // the program's own libembree3, or one in the global scope
  if (!f) {
    dlerror();
    if (void* h = local_embree3()) f = real_dlsym(h, name);
    if (!f) dlerror();
  }
  if (!f)
    refuse_capture(std::string("the application called Embree's ") + name +
                   " but no libembree3 that defines it is loaded where the capture shim can reach it "
                   "(Embree 3 is captured through a shared libembree3 only)");
  if (starts_with(base_name(defining_file(f).c_str()), "libembree4."))
    refuse_capture(std::string("the application uses Embree 4 (") + defining_file(f) +
                   "): the capture shim speaks Embree 3's API only");
  return f;
}

bool embree_loaded() {
  void* f = dlsym(RTLD_NEXT, "rtcNewDevice");
  if (!f) dlerror();
  return f || local_embree3();
}

std::string embree_out_of_reach() {
  const auto* ns = reinterpret_cast<const r_debug_extended*>(&_r_debug);
  const bool every_namespace = _r_debug.r_version >= 2;  // glibc 2.35: the namespaces chained by r_next
  for (int index = 0; ns; ns = every_namespace ? ns->r_next : nullptr, ++index) {
    const std::string path = embree_in_namespace(ns->base.r_map);
    if (path.empty()) continue;
    if (index > 0) return out_of_namespace_reason(path);
    if (starts_with(base_name(path.c_str()), "libembree4."))
      return "the application loaded Embree 4 (" + path + "): the capture shim speaks Embree 3's API only";
  }
  return "";
}

void check_handle_namespace(void* handle) {
  Lmid_t lmid = LM_ID_BASE;
  link_map* map = nullptr;
  if (dlinfo(handle, RTLD_DI_LMID, &lmid) != 0 || lmid == LM_ID_BASE ||
      dlinfo(handle, RTLD_DI_LINKMAP, &map) != 0 || !map) {
    dlerror();
    return;
  }
  while (map->l_prev) map = map->l_prev;
  const std::string path = embree_in_namespace(map);
  if (!path.empty()) refuse_capture(out_of_namespace_reason(path));
}

void* embree_entry_for(const char* name, void* found) {
  void* own = shim_handle() ? real_dlsym(shim_handle(), name) : nullptr;
  dlerror();  // a name the shim does not interpose: no error of the shim's left for the application
  if (!own || own == found || defining_file(own) != defining_file(reinterpret_cast<void*>(&embree_function)))
    return found;
  return own;
}

}  // namespace vbsim::shim
