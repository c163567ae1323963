#include "trace/rtcore_ray_import.h"

#include <cmath>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "trace/binary_trace_format.h"
#include "trace/trace_header_json.h"

namespace vbsim {

namespace {

constexpr std::size_t kRecordsPerChunk = 4096;

void store_f32(uint8_t* p, float x) {
  uint32_t bits;
  std::memcpy(&bits, &x, 4);
  for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(bits >> (8 * i));
}

}  // namespace

RtcoreRayReader::RtcoreRayReader(std::string path, std::string scene_path)
    : path_(std::move(path)) {
  std::ifstream in = RecordFileReader::open_file(path_);
  header_.scene = scene_relative_to(scene_path, path_);
  header_.scene_path = std::move(scene_path);
  header_.description =
      fmt::format("rtcore-systemc ray file {}", std::filesystem::path(path_).filename().string());
  records_ = RecordFileReader(path_, std::move(in), 0,
                              {kRtcoreRayRecordBytes, kRecordsPerChunk,
                               "7 float32: ox oy oz dx dy dz tmax"});
}

bool RtcoreRayReader::next(TraceRay& out) {
  const uint8_t* r = records_.next();
  if (r == nullptr) return false;
  int64_t index = records_.records_read() - 1;
  out = TraceRay{};
  out.id = index;
  out.o = {load_le_f32(r), load_le_f32(r + 4), load_le_f32(r + 8)};
  out.d = {load_le_f32(r + 12), load_le_f32(r + 16), load_le_f32(r + 20)};
  out.tmax = load_le_f32(r + 24);
  // Ids are record indices, so unique by construction: the stateless rules suffice.
  TraceFieldProblem problem;
  if (!check_trace_ray(out, triangle_count_, problem))
    throw TraceError::at_record(path_, index, problem.field, problem.message);
  return true;
}

TraceError RtcoreRayReader::error_at_last_ray(const std::string& field,
                                              const std::string& message) const {
  return TraceError::at_record(path_, records_.records_read() - 1, field, message);
}

RtcoreRayWriter::RtcoreRayWriter(std::string path)
    : path_(std::move(path)), records_(path_, kRtcoreRayRecordBytes, kRecordsPerChunk) {}

void RtcoreRayWriter::write(const TraceRay& ray) {
  records_.require_open();
  const int64_t index = records_.records_written();
  TraceFieldProblem problem;
  if (!check_trace_ray(ray, -1, problem))
    throw TraceError::at_record(path_, index, problem.field, problem.message);
  if (!(ray.tmin == 0.0f && !std::signbit(ray.tmin)))
    throw TraceError::at_record(path_, index, "tmin",
                                fmt::format("{} cannot be written: rtcore ray files have tmin 0",
                                            ray.tmin));
  records_.append([&](uint8_t* r) {
    for (int i = 0; i < 3; ++i) store_f32(r + 4 * i, ray.o[i]);
    for (int i = 0; i < 3; ++i) store_f32(r + 12 + 4 * i, ray.d[i]);
    store_f32(r + 24, ray.tmax);
  });
}

}  // namespace vbsim
