#include "trace/trace_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>

#include <fmt/format.h>

#include "trace/binary_trace_format.h"
#include "trace/binary_trace_reader.h"
#include "trace/binary_trace_writer.h"
#include "trace/text_trace_reader.h"
#include "trace/text_trace_writer.h"
#include "trace/trace_header_json.h"

namespace vbsim {

bool is_binary_trace_path(const std::string& path) {
  const std::string ext = kBinaryTraceExtension;
  return path.size() >= ext.size() && path.compare(path.size() - ext.size(), ext.size(), ext) == 0;
}

std::unique_ptr<TraceSource> open_trace(const std::string& path) {
  // Opened once, and only its first byte peeked: a pipe (/dev/stdin, <(...)) works too.
  std::ifstream in(path, std::ios::in | std::ios::binary);
  if (!in) throw TraceError::in_file(path, fmt::format("cannot open: {}", std::strerror(errno)));
  // Text traces start with '{', '#' or white space; the binary magic with 'V'.
  if (in.peek() == kBinaryTraceMagic[0]) return std::make_unique<BinaryTraceReader>(path, std::move(in));
  return std::make_unique<TextTraceReader>(path, std::move(in));
}

std::unique_ptr<TraceSink> create_trace_writer(const std::string& path, const TraceHeader& header) {
  if (is_binary_trace_path(path)) return std::make_unique<BinaryTraceWriter>(path, header);
  return std::make_unique<TextTraceWriter>(path, header);
}

int64_t copy_trace(TraceSource& in, TraceSink& out) {
  TraceRay ray;
  int64_t count = 0;
  while (in.next(ray)) {
    out.write(ray);
    ++count;
  }
  return count;
}

int64_t convert_trace_file(const std::string& in_path, const std::string& out_path) {
  std::unique_ptr<TraceSource> in = open_trace(in_path);
  TraceHeader header = in->header();
  header.scene = scene_relative_to(header.scene_path, out_path);
  header.scene_path = resolve_scene_path(header.scene, out_path);
  std::unique_ptr<TraceSink> out = create_trace_writer(out_path, header);
  int64_t count = copy_trace(*in, *out);
  out->close();
  return count;
}

}  // namespace vbsim
