// EmbreeDevice: an owned Embree device whose errors become exceptions, shared
// by the BVH builder and the Embree reference intersector.
//
// Contract: the device runs Embree with one worker thread ("threads=1"), so a
// build over the same input always produces the same tree (Embree's parallel
// partitioning may otherwise reorder primitives inside leaves from run to run).
#pragma once
#include <embree3/rtcore.h>

#include <mutex>
#include <string>

namespace vbsim {

class EmbreeDevice {
 public:
  /// Creates the device; throws SceneError when Embree cannot start.
  /// `settings`: more of Embree's device configuration, appended to
  /// "threads=1,verbose=0" (Embree ignores a key it does not know: callers
  /// pass only settings they have checked).
  explicit EmbreeDevice(const std::string& settings = "");
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice get() const { return device_; }

  /// Throws SceneError("Embree <what> failed: <message>") if any Embree call on
  /// this device reported an error since the last check; clears the error.
  void check(const char* what);

 private:
  static void on_error(void* self, RTCError code, const char* message);

  RTCDevice device_ = nullptr;
  std::mutex mutex_;        // guards first_error_ (Embree may report from worker threads)
  std::string first_error_;  // empty when no error is pending
};

}  // namespace vbsim
