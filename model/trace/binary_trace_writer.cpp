#include "trace/binary_trace_writer.h"

#include "trace/binary_trace_format.h"
#include "trace/trace_header_json.h"

namespace vbsim {

namespace {

constexpr std::size_t kRecordsPerWrite = 1024;

/// The bytes before the first record: preamble, then the header JSON padded
/// with spaces. Throws TraceError about the header, naming `path`.
std::string binary_trace_prefix(const std::string& path, const TraceHeader& header, uint32_t version) {
  std::string header_text;
  try {
    header_text = trace_header_json(header);
  } catch (const TraceFieldProblem& p) {
    throw TraceError::in_header(path, p.field, p.message);
  }
  if (header_text.size() > kBinaryTraceMaxHeaderBytes)
    throw TraceError::in_header(path, "", "header JSON is longer than 16 MiB");
  uint8_t preamble[kBinaryTracePreambleBytes];
  encode_binary_trace_preamble(static_cast<uint32_t>(header_text.size()), preamble, version);
  header_text.resize(binary_trace_padded_header_bytes(header_text.size()), ' ');
  return std::string(reinterpret_cast<const char*>(preamble), sizeof preamble) + header_text;
}

}  // namespace

BinaryTraceWriter::BinaryTraceWriter(std::string path, const TraceHeader& header)
    : path_(std::move(path)),
      version_(binary_trace_layout_for(header)),
      records_(path_, binary_trace_record_bytes(version_), kRecordsPerWrite,
               binary_trace_prefix(path_, header, version_)) {}

void BinaryTraceWriter::write(const TraceRay& ray) {
  records_.require_open();
  TraceFieldProblem problem;
  if (!validator_.check(ray, problem))
    throw TraceError::at_record(path_, records_.records_written(), problem.field, problem.message);
  if (ray.has_reference && !binary_layout_has_reference(version_))
    throw TraceError::at_record(path_, records_.records_written(), "reference",
                                "the header names no reference (its \"reference\" field says what gave the answers)");
  if (ray.mask != kAllMaskBits && !binary_layout_has_mask(version_))
    throw TraceError::at_record(path_, records_.records_written(), "mask",
                                "the header declares no ray masks (triangle_masks)");
  records_.append([&](uint8_t* record) { encode_binary_trace_record(ray, record, version_); });
}

}  // namespace vbsim
