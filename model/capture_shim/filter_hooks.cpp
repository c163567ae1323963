// The geometry filter setters the shim interposes, and the trampolines that
// count filter calls per thread (filter_watch.h).
#include <array>
#include <atomic>
#include <cstring>
#include <mutex>
#include <utility>

#include "capture/raw_capture_format.h"
#include "capture_output.h"
#include "filter_watch.h"
#include "real_embree.h"
#include "scene_registry.h"

namespace vbsim::shim {

namespace {

constexpr std::size_t kTrampolines = 64;  // distinct filter functions watched per process
constexpr unsigned kMaxLanes = 16;         // Embree's widest packet
/// RTCHitN fields: Ng (3), u, v, primID, geomID, then instID per instance level, N lanes each.
constexpr std::size_t kHitFields = 7 + RTC_MAX_INSTANCE_LEVEL_COUNT;
constexpr unsigned kTfarField = 8;  // RTCRayN: org (3), tnear, dir (3), time, tfar, ...

thread_local uint64_t t_filter_changes = 0;
std::atomic<RTCFilterFunctionN> g_filters[kTrampolines];
std::atomic<uint64_t> g_unwatched{0};

/// Calls `f` and counts the call on this thread when it rejected a candidate
/// hit (a valid lane cleared) or changed the candidate hit or the ray's tfar:
/// a filter that accepts the hit as Embree found it leaves the answer as it is.
void call_watched(RTCFilterFunctionN f, const RTCFilterFunctionNArguments* args) {
  const unsigned n = args->N;
  if (n > kMaxLanes || !args->valid || !args->hit || !args->ray) {
    ++t_filter_changes;  // not a layout the shim can compare: the call may have changed the answer
    return f(args);
  }
  int valid[kMaxLanes];
  unsigned char hit[kHitFields * kMaxLanes * 4];
  float tfar[kMaxLanes];
  const float* ray_tfar = reinterpret_cast<const float*>(args->ray) + kTfarField * n;
  std::memcpy(valid, args->valid, n * sizeof(int));
  std::memcpy(hit, args->hit, kHitFields * n * 4);
  std::memcpy(tfar, ray_tfar, n * sizeof(float));
  f(args);
  if (std::memcmp(valid, args->valid, n * sizeof(int)) != 0 || std::memcmp(hit, args->hit, kHitFields * n * 4) != 0 ||
      std::memcmp(tfar, ray_tfar, n * sizeof(float)) != 0)
    ++t_filter_changes;
}

template <std::size_t K>
void trampoline(const RTCFilterFunctionNArguments* args) {
  call_watched(g_filters[K].load(std::memory_order_acquire), args);
}

template <std::size_t... K>
constexpr std::array<RTCFilterFunctionN, sizeof...(K)> make_trampolines(std::index_sequence<K...>) {
  return {&trampoline<K>...};
}
constexpr auto kTrampolineTable = make_trampolines(std::make_index_sequence<kTrampolines>{});

/// The trampoline that calls `f` (null stays null); `f` itself when every trampoline is taken.
RTCFilterFunctionN watched(RTCFilterFunctionN f) {
  if (!f) return f;
  static std::mutex m;
  std::lock_guard<std::mutex> lock(m);
  for (std::size_t k = 0; k < kTrampolines; ++k) {
    if (kTrampolineTable[k] == f) return f;  // already one of ours
    RTCFilterFunctionN cur = g_filters[k].load(std::memory_order_relaxed);
    if (cur == f) return kTrampolineTable[k];
    if (!cur) {
      g_filters[k].store(f, std::memory_order_release);
      return kTrampolineTable[k];
    }
  }
  ++g_unwatched;
  return f;
}

}  // namespace

uint64_t filter_changes_on_this_thread() { return t_filter_changes; }
uint64_t unwatched_filter_functions() { return g_unwatched.load(); }

uint32_t FilterWatch::flags() const {
  uint32_t f = 0;
  if (filter_changes_on_this_thread() != before_) f |= capture::kRawFilterChanged;
  if (context_filter_) f |= capture::kRawContextFilter;
  return f;
}

}  // namespace vbsim::shim

using namespace vbsim::shim;

void rtcSetGeometryIntersectFilterFunction(RTCGeometry geometry, RTCFilterFunctionN filter) {
  VBSIM_REAL(rtcSetGeometryIntersectFilterFunction);
  if (!capture_enabled()) return real(geometry, filter);
  real(geometry, watched(filter));
  on_filter(geometry, vbsim::capture::kRawIntersectFilter, filter != nullptr);
}

void rtcSetGeometryOccludedFilterFunction(RTCGeometry geometry, RTCFilterFunctionN filter) {
  VBSIM_REAL(rtcSetGeometryOccludedFilterFunction);
  if (!capture_enabled()) return real(geometry, filter);
  real(geometry, watched(filter));
  on_filter(geometry, vbsim::capture::kRawOccludedFilter, filter != nullptr);
}
