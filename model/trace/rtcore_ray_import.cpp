#include "trace/rtcore_ray_import.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "trace/binary_trace_format.h"
#include "trace/trace_header_json.h"

namespace vbsim {

namespace {

constexpr std::size_t kRecordsPerChunk = 4096;

std::string truncated_record_message(std::size_t bytes) {
  return fmt::format("truncated: the file ends {} bytes into this {}-byte record "
                     "(7 float32: ox oy oz dx dy dz tmax)",
                     bytes, kRtcoreRayRecordBytes);
}

void store_f32(uint8_t* p, float x) {
  uint32_t bits;
  std::memcpy(&bits, &x, 4);
  for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(bits >> (8 * i));
}

}  // namespace

RtcoreRayReader::RtcoreRayReader(std::string path, std::string scene_path)
    : path_(std::move(path)) {
  in_.open(path_, std::ios::in | std::ios::binary);
  if (!in_) throw TraceError::in_file(path_, fmt::format("cannot open: {}", std::strerror(errno)));
  header_.scene = scene_relative_to(scene_path, path_);
  header_.scene_path = std::move(scene_path);
  header_.description =
      fmt::format("rtcore-systemc ray file {}", std::filesystem::path(path_).filename().string());

  std::error_code ec;
  uintmax_t size = std::filesystem::file_size(path_, ec);
  if (!ec) {
    record_count_ = static_cast<int64_t>(size / kRtcoreRayRecordBytes);
    if (size % kRtcoreRayRecordBytes != 0)
      throw TraceError::at_record(path_, record_count_, "",
                                  truncated_record_message(size % kRtcoreRayRecordBytes));
  }
  buffer_.resize(kRecordsPerChunk * kRtcoreRayRecordBytes);
}

bool RtcoreRayReader::fill() {
  std::size_t kept = trailing_bytes_;
  std::memmove(buffer_.data(), buffer_.data() + end_, kept);
  in_.read(reinterpret_cast<char*>(buffer_.data() + kept),
           static_cast<std::streamsize>(buffer_.size() - kept));
  std::size_t have = kept + static_cast<std::size_t>(in_.gcount());
  if (in_.bad()) throw TraceError::at_record(path_, next_record_, "", "read error");
  pos_ = 0;
  end_ = have / kRtcoreRayRecordBytes * kRtcoreRayRecordBytes;
  trailing_bytes_ = have - end_;
  if (end_ > 0) return true;
  if (trailing_bytes_ > 0)
    throw TraceError::at_record(path_, next_record_, "", truncated_record_message(trailing_bytes_));
  return false;
}

bool RtcoreRayReader::next(TraceRay& out) {
  if (pos_ == end_ && !fill()) return false;
  const uint8_t* r = buffer_.data() + pos_;
  pos_ += kRtcoreRayRecordBytes;
  int64_t index = next_record_++;
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
  return TraceError::at_record(path_, next_record_ - 1, field, message);
}

RtcoreRayWriter::RtcoreRayWriter(std::string path) : path_(std::move(path)) {
  out_.open(path_, std::ios::out | std::ios::binary | std::ios::trunc);
  if (!out_)
    throw TraceError::in_file(path_, fmt::format("cannot create: {}", std::strerror(errno)));
  buffer_.resize(kRecordsPerChunk * kRtcoreRayRecordBytes);
}

RtcoreRayWriter::~RtcoreRayWriter() {
  if (!closed_) {
    try {
      close();
    } catch (const TraceError&) {
      // Destructors must not throw; close() reports errors to callers who ask.
    }
  }
}

void RtcoreRayWriter::write(const TraceRay& ray) {
  if (closed_) throw TraceError::in_file(path_, "write after close");
  TraceFieldProblem problem;
  if (!check_trace_ray(ray, -1, problem))
    throw TraceError::at_record(path_, records_, problem.field, problem.message);
  if (!(ray.tmin == 0.0f && !std::signbit(ray.tmin)))
    throw TraceError::at_record(path_, records_, "tmin",
                                fmt::format("{} cannot be written: rtcore ray files have tmin 0",
                                            ray.tmin));
  uint8_t* r = buffer_.data() + used_;
  for (int i = 0; i < 3; ++i) store_f32(r + 4 * i, ray.o[i]);
  for (int i = 0; i < 3; ++i) store_f32(r + 12 + 4 * i, ray.d[i]);
  store_f32(r + 24, ray.tmax);
  used_ += kRtcoreRayRecordBytes;
  ++records_;
  if (used_ == buffer_.size()) flush_buffer();
}

void RtcoreRayWriter::flush_buffer() {
  out_.write(reinterpret_cast<const char*>(buffer_.data()), static_cast<std::streamsize>(used_));
  used_ = 0;
  if (!out_) throw TraceError::in_file(path_, "write failed");
}

void RtcoreRayWriter::close() {
  if (closed_) return;
  closed_ = true;
  flush_buffer();
  out_.close();
  if (!out_) throw TraceError::in_file(path_, "write failed while closing");
}

}  // namespace vbsim
