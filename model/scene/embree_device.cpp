#include "scene/embree_device.h"

#include <fmt/format.h>

#include "scene/scene.h"

namespace vbsim {

namespace {

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
  }
  return "unrecognised error code";
}

}  // namespace

EmbreeDevice::EmbreeDevice(const std::string& settings) {
  const std::string config = settings.empty() ? "threads=1,verbose=0" : "threads=1,verbose=0," + settings;
  device_ = rtcNewDevice(config.c_str());
  if (device_ == nullptr)
    throw SceneError(fmt::format("Embree rtcNewDevice failed: {}", error_name(rtcGetDeviceError(nullptr))));
  rtcSetDeviceErrorFunction(device_, &EmbreeDevice::on_error, this);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

void EmbreeDevice::on_error(void* self, RTCError code, const char* message) {
  auto* device = static_cast<EmbreeDevice*>(self);
  std::lock_guard<std::mutex> lock(device->mutex_);
  if (device->first_error_.empty())
    device->first_error_ = fmt::format("{} ({})", message ? message : "", error_name(code));
}

void EmbreeDevice::check(const char* what) {
  std::string error;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    error.swap(first_error_);
  }
  const RTCError code = rtcGetDeviceError(device_);  // also clears Embree's own sticky code
  if (error.empty() && code != RTC_ERROR_NONE) error = error_name(code);
  if (!error.empty()) throw SceneError(fmt::format("Embree {} failed: {}", what, error));
}

}  // namespace vbsim
