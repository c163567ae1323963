#include "trace/text_trace_reader.h"

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "io/line_reader.h"
#include "trace/text_ray_parse.h"
#include "trace/trace_header_json.h"
#include "trace/trace_json_values.h"

namespace vbsim {

namespace {

/// Lines read ahead at a time when parsing on several threads.
constexpr std::size_t kAheadLines = 4096;

bool is_blank_or_comment(const std::string& line) {
  for (char c : line) {
    if (c == ' ' || c == '\t' || c == '\r') continue;
    return c == '#';
  }
  return true;
}

}  // namespace

TextTraceReader::TextTraceReader(std::string path)
    : TextTraceReader(path, std::ifstream(path, std::ios::in | std::ios::binary)) {}

TextTraceReader::TextTraceReader(std::string path, std::ifstream in)
    : path_(std::move(path)), in_(std::move(in)) {
  if (!in_) throw TraceError::in_file(path_, fmt::format("cannot open: {}", std::strerror(errno)));
  if (!read_content_line(line_))
    throw TraceError::in_file(path_, "empty: no header line");
  line_number_ = read_line_;
  try {
    header_ = parse_trace_header(parse_json_object_line(line_), path_);
  } catch (const TraceFieldProblem& p) {
    throw TraceError::at_line(path_, line_number_, p.field, p.message);
  }
}

bool TextTraceReader::read_content_line(std::string& line) {
  if (stopped_) return false;
  for (LineRead r; (r = read_bounded_line(in_, line)) != LineRead::kEnd;) {
    ++read_line_;
    if (r == LineRead::kTooLong) {
      stopped_ = true;  // the line's rest would be read as more lines
      line.clear();
      throw TraceError::at_line(path_, read_line_, "",
                                fmt::format("longer than {} MiB, the limit of a trace line (docs/trace-format.md)",
                                            kMaxTextLineBytes >> 20));
    }
    if (!is_blank_or_comment(line)) return true;
  }
  if (in_.bad()) throw TraceError::at_line(path_, read_line_ + 1, "", "read error");
  return false;
}

void TextTraceReader::validate(const TraceRay& out) {
  TraceFieldProblem problem;
  if (!validator_.check(out, problem))
    throw TraceError::at_line(path_, line_number_, problem.field, problem.message);
  if (out.has_reference && header_.reference.empty())
    throw TraceError::at_line(path_, line_number_, "reference",
                              "the header names no reference (its \"reference\" field says what gave the answers)");
  if (out.mask != kAllMaskBits && !header_.triangle_masks)
    throw TraceError::at_line(path_, line_number_, "mask",
                              "the header declares no ray masks (its \"triangle_masks\" field, [] when only rays "
                              "carry masks)");
}

bool TextTraceReader::next(TraceRay& out) {
  if (parse_threads_ > 1 || ahead_next_ < ahead_.size() || ahead_error_) return next_ahead(out);
  bool more = false;
  try {
    more = read_content_line(line_);
  } catch (const TraceError&) {
    line_number_ = read_line_;
    throw;
  }
  line_number_ = read_line_;
  if (!more) return false;
  try {
    parse_trace_ray_line(line_, out);
  } catch (const TraceFieldProblem& p) {
    throw TraceError::at_line(path_, line_number_, p.field, p.message);
  }
  validate(out);
  return true;
}

void TextTraceReader::read_ahead() {
  ahead_.clear();
  ahead_next_ = 0;
  while (ahead_.size() < kAheadLines) {
    std::string& line = ahead_.free_line();
    try {
      if (!read_content_line(line)) break;
    } catch (const TraceError&) {  // thrown once the lines before it are handed out
      ahead_error_ = std::current_exception();
      ahead_error_line_ = read_line_;
      break;
    }
    ahead_.commit(read_line_);
  }
  ahead_.parse(parse_threads_);
}

bool TextTraceReader::next_ahead(TraceRay& out) {
  if (ahead_next_ == ahead_.size()) {
    if (ahead_error_) {
      const std::exception_ptr error = ahead_error_;
      ahead_error_ = nullptr;
      line_number_ = ahead_error_line_;
      std::rethrow_exception(error);
    }
    if (parse_threads_ <= 1) return next(out);
    read_ahead();
    if (ahead_.size() == 0) {  // the end, or an error at the block's first line
      if (ahead_error_) return next_ahead(out);
      line_number_ = read_line_;
      return false;
    }
  }
  const std::size_t i = ahead_next_++;
  line_number_ = ahead_.line_number(i);
  try {
    ahead_.take(i, out);
  } catch (const TraceFieldProblem& p) {
    throw TraceError::at_line(path_, line_number_, p.field, p.message);
  }
  validate(out);
  return true;
}

TraceError TextTraceReader::error_at_last_ray(const std::string& field,
                                              const std::string& message) const {
  return TraceError::at_line(path_, line_number_, field, message);
}

}  // namespace vbsim
