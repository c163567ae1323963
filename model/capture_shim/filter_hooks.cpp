// The geometry filter setters the shim interposes, the trampolines that watch
// the application's filter functions, and FilterWatch (filter_watch.h).
#include <array>
#include <atomic>
#include <cstring>
#include <mutex>
#include <utility>

#include "capture_output.h"
#include "filter_watch.h"
#include "real_embree.h"
#include "scene_registry.h"

namespace vbsim::shim {

namespace {

using capture::RawRay;

constexpr std::size_t kTrampolines = 64;  // distinct filter functions watched per process
constexpr unsigned kMaxLanes = FilterWatch::kMaxLanes;
/// RTCHitN fields: Ng (3), u, v, primID, geomID, then instID per instance level, N lanes each.
constexpr std::size_t kHitFields = 7 + RTC_MAX_INSTANCE_LEVEL_COUNT;
constexpr unsigned kPrimField = 5, kGeomField = 6, kInstField = 7;
constexpr unsigned kTfarField = 8;  // RTCRayN: org (3), tnear, dir (3), time, tfar, ...

thread_local FilterWatch* t_watch = nullptr;
std::atomic<RTCFilterFunctionN> g_filters[kTrampolines];
std::atomic<uint64_t> g_unwatched{0};

uint32_t hit_field(const unsigned char* hit, unsigned n, unsigned field, unsigned lane) {
  uint32_t v;
  std::memcpy(&v, hit + (field * n + lane) * 4, 4);
  return v;
}

/// Calls `f` and reports to the thread's watch, lane by lane, a rejected
/// candidate (valid cleared) or any other change of the candidate hit or the
/// ray's tfar: a filter that accepts the hit as Embree found it changes nothing.
void call_watched(RTCFilterFunctionN f, const RTCFilterFunctionNArguments* args) {
  FilterWatch* watch = FilterWatch::current();
  const unsigned n = args->N;
  if (!watch) return f(args);  // outside any ray call the shim records
  if (n == 0 || n > kMaxLanes || !args->valid || !args->hit || !args->ray) {
    f(args);  // not a layout the shim can compare: the call may have changed any answer
    return watch->changed(n, kMaxLanes);
  }
  int valid[kMaxLanes];
  unsigned char hit[kHitFields * kMaxLanes * 4];
  float tfar[kMaxLanes];
  const float* ray_tfar = reinterpret_cast<const float*>(args->ray) + kTfarField * n;
  std::memcpy(valid, args->valid, n * sizeof(int));
  std::memcpy(hit, args->hit, kHitFields * n * 4);
  std::memcpy(tfar, ray_tfar, n * sizeof(float));
  f(args);
  const auto* hit_after = reinterpret_cast<const unsigned char*>(args->hit);
  for (unsigned i = 0; i < n; ++i) {
    if (valid[i] == 0) continue;  // not a candidate in this call
    if (args->valid[i] == 0) {
      watch->rejected(n, i, hit_field(hit, n, kGeomField, i), hit_field(hit, n, kPrimField, i),
                      hit_field(hit, n, kInstField, i));
      continue;
    }
    bool same = std::memcmp(&tfar[i], &ray_tfar[i], sizeof(float)) == 0;
    for (std::size_t k = 0; k < kHitFields && same; ++k)
      same = std::memcmp(hit + (k * n + i) * 4, hit_after + (k * n + i) * 4, 4) == 0;
    if (!same) watch->changed(n, i);
  }
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

bool is_trampoline(RTCFilterFunctionN f) {
  for (RTCFilterFunctionN t : kTrampolineTable)
    if (t == f) return true;
  return false;
}

}  // namespace

RTCFilterFunctionN watched_filter(RTCFilterFunctionN f) {
  if (!f) return f;
  // The last function looked up on this thread: a context filter is looked up on every call.
  thread_local RTCFilterFunctionN last_f = nullptr, last_t = nullptr;
  if (f == last_f) return last_t;
  static std::mutex m;
  std::lock_guard<std::mutex> lock(m);
  RTCFilterFunctionN t = f;
  for (std::size_t k = 0; k < kTrampolines; ++k) {
    if (kTrampolineTable[k] == f) break;  // already one of ours
    RTCFilterFunctionN cur = g_filters[k].load(std::memory_order_relaxed);
    if (cur == f) {
      t = kTrampolineTable[k];
      break;
    }
    if (!cur) {
      g_filters[k].store(f, std::memory_order_release);
      t = kTrampolineTable[k];
      break;
    }
    if (k + 1 == kTrampolines) ++g_unwatched;
  }
  last_f = f, last_t = t;
  return t;
}

uint64_t unwatched_filter_functions() { return g_unwatched.load(); }

FilterWatch::FilterWatch(RTCIntersectContext* ctx, unsigned lanes, bool attributable)
    : lanes_(lanes), attributable_(attributable && lanes <= kMaxLanes), ctx_(ctx), outer_(t_watch) {
  // A context already swapped (a filter tracing with its call's own context) stays as it is.
  if (ctx && ctx->filter && !is_trampoline(ctx->filter)) {
    context_filter_ = ctx->filter;
    const RTCFilterFunctionN t = watched_filter(ctx->filter);
    context_unwatched_ = t == ctx->filter;
    ctx->filter = t;
  }
  t_watch = this;
}

FilterWatch::~FilterWatch() {
  if (context_filter_) ctx_->filter = context_filter_;
  t_watch = outer_;
}

FilterWatch* FilterWatch::current() { return t_watch; }

void FilterWatch::rejected(unsigned n, unsigned lane, uint32_t geom, uint32_t prim, uint32_t inst) {
  if (!maps(n, lane)) {
    unmatched_ = true;
    return;
  }
  Lane& l = lane_[lane];
  if (l.rejections == 0) l.geom = geom, l.prim = prim, l.inst = inst;
  else if (l.geom != geom || l.prim != prim || l.inst != inst) l.changed = true;  // a second primitive
  ++l.rejections;
}

void FilterWatch::changed(unsigned n, unsigned lane) {
  if (!maps(n, lane)) unmatched_ = true;
  else lane_[lane].changed = true;
}

void FilterWatch::describe(unsigned lane, RawRay& r) const {
  uint32_t f = 0;
  if (context_unwatched_) f |= capture::kRawContextFilter;
  if (unmatched_) f |= capture::kRawFilterChanged;
  if (lane < kMaxLanes) {
    const Lane& l = lane_[lane];
    if (l.changed) f |= capture::kRawFilterChanged;
    if (l.rejections > 0) {
      f |= capture::kRawFilterRejected;
      r.rejected_geom = l.geom, r.rejected_prim = l.prim, r.rejected_inst = l.inst;
      r.rejections = l.rejections;
    }
  }
  r.flags = f;
}

}  // namespace vbsim::shim

using namespace vbsim::shim;

void rtcSetGeometryIntersectFilterFunction(RTCGeometry geometry, RTCFilterFunctionN filter) {
  VBSIM_REAL(rtcSetGeometryIntersectFilterFunction);
  if (!capture_enabled()) return real(geometry, filter);
  real(geometry, watched_filter(filter));
  on_filter(geometry, vbsim::capture::kRawIntersectFilter, filter != nullptr);
}

void rtcSetGeometryOccludedFilterFunction(RTCGeometry geometry, RTCFilterFunctionN filter) {
  VBSIM_REAL(rtcSetGeometryOccludedFilterFunction);
  if (!capture_enabled()) return real(geometry, filter);
  real(geometry, watched_filter(filter));
  on_filter(geometry, vbsim::capture::kRawOccludedFilter, filter != nullptr);
}
