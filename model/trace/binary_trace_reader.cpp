#include "trace/binary_trace_reader.h"

#include <cstring>

#include <fmt/format.h>

#include "trace/binary_trace_format.h"
#include "trace/trace_header_json.h"
#include "trace/trace_json_values.h"

namespace vbsim {

namespace {
constexpr std::size_t kRecordsPerRead = 1024;
}

BinaryTraceReader::BinaryTraceReader(std::string path)
    : BinaryTraceReader(path, RecordFileReader::open_file(path)) {}

BinaryTraceReader::BinaryTraceReader(std::string path, std::ifstream in) : path_(std::move(path)) {

  uint8_t preamble[kBinaryTracePreambleBytes];
  in.read(reinterpret_cast<char*>(preamble), sizeof preamble);
  std::size_t got = static_cast<std::size_t>(in.gcount());
  if (got < sizeof kBinaryTraceMagic ||
      std::memcmp(preamble, kBinaryTraceMagic, sizeof kBinaryTraceMagic) != 0)
    throw TraceError::in_file(path_, "not a binary vbsim trace (no \"VBSIMTRB\" magic)");
  if (got < sizeof preamble)
    throw TraceError::in_file(path_, "truncated: the file ends inside its 16-byte preamble");
  const uint32_t version = load_le_u32(preamble + 8);
  if (version < kBinaryTraceLayoutVersion || version > kBinaryTraceMaskLayoutVersion)
    throw TraceError::in_file(path_, fmt::format("unsupported binary layout version {} (this "
                                                 "reader reads {} to {})",
                                                 version, kBinaryTraceLayoutVersion,
                                                 kBinaryTraceMaskLayoutVersion));
  version_ = version;
  uint32_t header_bytes = load_le_u32(preamble + 12);
  if (header_bytes == 0 || header_bytes > kBinaryTraceMaxHeaderBytes)
    throw TraceError::in_header(path_, "", fmt::format("implausible header length {}", header_bytes));

  std::size_t padded = binary_trace_padded_header_bytes(header_bytes);
  std::string header_text(padded, ' ');
  in.read(header_text.data(), static_cast<std::streamsize>(padded));
  if (static_cast<std::size_t>(in.gcount()) != padded)
    throw TraceError::in_header(path_, "", fmt::format("truncated: the file ends inside the "
                                                       "{}-byte header",
                                                       padded));
  header_text.resize(header_bytes);
  // The JSON must fill exactly the stated length: a length that runs past the
  // object (into the padding or the records) would swallow rays unseen. The
  // JSON parser takes a NUL byte as the end of its input, so one is refused first.
  const std::size_t nul = header_text.find('\0');
  if (nul != std::string::npos)
    throw TraceError::in_header(path_, "", fmt::format("the stated header length {} runs past the header JSON "
                                                       "(a NUL byte at header byte {})",
                                                       header_bytes, nul));
  if (header_text.back() != '}')
    throw TraceError::in_header(path_, "", fmt::format("the header JSON does not end at its stated length {} "
                                                       "(the object's closing '}}' must be its last byte)",
                                                       header_bytes));
  try {
    header_ = parse_trace_header(parse_json_object_line(header_text), path_);
  } catch (const TraceFieldProblem& p) {
    throw TraceError::in_header(path_, p.field, p.message);
  }
  if (header_.triangle_masks.has_value() != binary_layout_has_mask(version_))
    throw TraceError::in_header(path_, "triangle_masks",
                                fmt::format("layout {} {} ray masks but the header {} them (layout 3 holds them, "
                                            "and only a header with triangle_masks selects it)",
                                            version_, binary_layout_has_mask(version_) ? "holds" : "has no room for",
                                            header_.triangle_masks ? "declares" : "does not declare"));

  records_ = RecordFileReader(path_, std::move(in), kBinaryTracePreambleBytes + padded,
                              {binary_trace_record_bytes(version_), kRecordsPerRead, ""});
}

bool BinaryTraceReader::next(TraceRay& out) {
  const uint8_t* record = records_.next();
  if (record == nullptr) return false;
  int64_t index = records_.records_read() - 1;
  TraceFieldProblem problem;
  if (!decode_binary_trace_record(record, out, problem, version_) || !validator_.check(out, problem))
    throw TraceError::at_record(path_, index, problem.field, problem.message);
  return true;
}

TraceError BinaryTraceReader::error_at_last_ray(const std::string& field,
                                                const std::string& message) const {
  return TraceError::at_record(path_, records_.records_read() - 1, field, message);
}

}  // namespace vbsim
