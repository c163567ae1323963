// Process-wide output of the capture shim: per-thread ray buffers written to
// rays-<image>-<k>.bin, scene snapshots, and the process summary written at
// exit or before an exec() (file layouts and the image name <pid>.<g>:
// model/capture/raw_capture_format.h). Every function may be
// called from any thread. The shim only reads what the application passes to
// Embree and what Embree returns; nothing here touches the application's data.
#pragma once
#include <cstdint>
#include <string>

#include "capture/raw_capture_format.h"

namespace vbsim::shim {

/// True when VBSIM_CAPTURE_DIR is set and the process has not started exiting.
bool capture_enabled();

/// Appends `ray` to the calling thread's buffer (flushed to its file when full,
/// at thread exit and at process exit).
void record_ray(const capture::RawRay& ray);

/// Counts one call of `api` (intersect or occluded) for the process summary.
void count_call(capture::RawApi api, bool occluded);

/// Writes `bytes` as the file `name` in the capture directory (whole, at once).
void write_capture_file(const std::string& name, const std::string& bytes);

/// The name of this process image's files, "<pid>.<g>" (claimed on first
/// use; a forked child and an exec'd image claim their own).
std::string capture_image();

/// Before the process replaces its image (exec): writes out every thread's
/// buffered records and the summary, marked as ended by an exec. If the exec
/// fails, capture goes on and the summary is written again at exit.
void prepare_for_exec();

/// Refuses to capture this process image: writes `why` as refused-<image>.txt
/// (when capturing) and on stderr, and ends the process with
/// capture::kShimRefusedStatus without running its exit handlers, before it
/// traces through an Embree the shim cannot see.
[[noreturn]] void refuse_capture(const std::string& why);

/// Whether the application's Embree honours ray masks (its device's
/// RTC_DEVICE_PROPERTY_RAY_MASK_SUPPORTED), for the summary.
void note_ray_masks(bool supported);

/// Counts scenes created and commits seen, for the summary.
void count_scene();
void count_commit();

}  // namespace vbsim::shim
