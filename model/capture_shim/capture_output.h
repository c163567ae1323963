// Process-wide output of the capture shim: per-thread ray buffers written to
// rays-<pid>-<k>.bin, scene snapshots, and the process summary written at exit
// (file layouts: model/capture/raw_capture_format.h). Every function may be
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

/// The process id the files are named after (updated in a forked child).
long capture_pid();

/// Counts scenes created and commits seen, for the summary.
void count_scene();
void count_commit();

}  // namespace vbsim::shim
