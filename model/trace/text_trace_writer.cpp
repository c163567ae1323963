#include "trace/text_trace_writer.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <iterator>

#include "trace/incomplete_reasons.h"
#include "trace/trace_header_json.h"
#include "trace/trace_json_values.h"

namespace vbsim {

namespace {

void text(fmt::memory_buffer& out, const char* s) {
  out.append(s, s + std::strlen(s));
}

bool is_positive_zero(float x) { return x == 0.0f && !std::signbit(x); }

}  // namespace

void append_trace_ray_json(fmt::memory_buffer& out, const TraceRay& ray) {
  auto it = std::back_inserter(out);
  fmt::format_to(it, "{{\"id\":{}", ray.id);
  if (ray.parent != -1) fmt::format_to(it, ",\"parent\":{}", ray.parent);
  if (ray.kind != RayKind::Primary) fmt::format_to(it, ",\"kind\":\"{}\"", ray_kind_name(ray.kind));
  text(out, ",\"o\":");
  append_json_vec3(out, ray.o);
  text(out, ",\"d\":");
  append_json_vec3(out, ray.d);
  if (!is_positive_zero(ray.tmin)) {
    text(out, ",\"tmin\":");
    append_json_float(out, ray.tmin);
  }
  if (!(std::isinf(ray.tmax) && ray.tmax > 0)) {
    text(out, ",\"tmax\":");
    append_json_float(out, ray.tmax);
  }
  if (ray.parent_prim != -1) fmt::format_to(it, ",\"parent_prim\":{}", ray.parent_prim);
  if (ray.has_parent_t) {
    text(out, ",\"parent_t\":");
    append_json_float(out, ray.parent_t);
  }
  if (ray.has_parent_uv) {
    text(out, ",\"parent_uv\":[");
    append_json_float(out, ray.parent_u);
    out.push_back(',');
    append_json_float(out, ray.parent_v);
    out.push_back(']');
  }
  if (ray.has_parent_ns) {
    text(out, ",\"parent_ns\":");
    append_json_vec3(out, ray.parent_ns);
  }
  if (ray.sign != -1) fmt::format_to(it, ",\"sign\":{}", static_cast<int>(ray.sign));
  if (ray.has_expect) {
    fmt::format_to(it, ",\"expect\":{{\"prim\":{}", ray.expect_prim);
    if (ray.has_expect_t) {
      text(out, ",\"t\":");
      append_json_double(out, ray.expect_t);
    }
    out.push_back('}');
  }
  if (ray.has_reference) {
    if (ray.reference_prim == kReferenceOccluded) {
      text(out, ",\"reference\":{\"occluded\":true}");
    } else if (ray.reference_prim == -1 && ray.kind == RayKind::Shadow) {
      text(out, ",\"reference\":{\"occluded\":false}");
    } else {
      fmt::format_to(it, ",\"reference\":{{\"prim\":{}", ray.reference_prim);
      if (ray.has_reference_t) {
        text(out, ",\"t\":");
        append_json_float(out, ray.reference_t);
      }
      out.push_back('}');
    }
  }
  if (ray.mask != kAllMaskBits) fmt::format_to(it, ",\"mask\":{}", ray.mask);
  if (ray.incomplete != 0) {
    text(out, ",\"incomplete\":[");
    bool first = true;
    for (int k = 0; k < kIncompleteReasonCount; ++k)
      if (ray.incomplete & (1u << k)) {
        fmt::format_to(it, "{}\"{}\"", first ? "" : ",", incomplete_reason_name(k));
        first = false;
      }
    out.push_back(']');
  }
  out.push_back('}');
}

TextTraceWriter::TextTraceWriter(std::string path, const TraceHeader& header)
    : path_(std::move(path)), masks_declared_(header.triangle_masks.has_value()) {
  std::string header_line;
  try {
    header_line = trace_header_json(header);
  } catch (const TraceFieldProblem& p) {
    throw TraceError::at_line(path_, 1, p.field, p.message);
  }
  try {
    out_ = std::make_unique<AtomicOutputFile>(path_, true);
  } catch (const OutputError& e) {
    throw TraceError::in_file(path_, e.message);
  }
  line_.append(header_line.data(), header_line.data() + header_line.size());
  flush_line();
}

void TextTraceWriter::flush_line() {
  line_.push_back('\n');
  std::ostream& out = out_->stream();
  out.write(line_.data(), static_cast<std::streamsize>(line_.size()));
  line_.clear();
  ++line_number_;
  if (!out) throw TraceError::at_line(path_, line_number_, "", fmt::format("write failed: {}", std::strerror(errno)));
}

void TextTraceWriter::write(const TraceRay& ray) {
  if (closed_) throw TraceError::in_file(path_, "write after close");
  TraceFieldProblem problem;
  if (!validator_.check(ray, problem))
    throw TraceError::at_line(path_, line_number_ + 1, problem.field, problem.message);
  if (ray.mask != kAllMaskBits && !masks_declared_)
    throw TraceError::at_line(path_, line_number_ + 1, "mask", "the header declares no ray masks (triangle_masks)");
  append_trace_ray_json(line_, ray);
  flush_line();
}

void TextTraceWriter::close() {
  if (closed_) return;
  closed_ = true;
  try {
    out_->commit();
  } catch (const OutputError& e) {
    throw TraceError::in_file(path_, e.message);
  }
}

}  // namespace vbsim
