// TraceSource and TraceSink: the streaming interfaces every trace reader and
// writer implements (text .jsonl, binary .vbt, rtcore ray files).
// Contract: a source yields rays in file order, one at a time, never holding
// the whole trace; every ray it yields has passed the format's validation.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "trace/trace_error.h"
#include "trace/trace_record.h"

namespace vbsim {

class TraceSource {
 public:
  virtual ~TraceSource() = default;

  /// The trace's header, read and validated when the source was opened.
  virtual const TraceHeader& header() const = 0;
  /// Reads the next ray into `out`; false at the end of the trace (then `out`
  /// is unspecified). Throws TraceError naming file, line/record and field.
  virtual bool next(TraceRay& out) = 0;
  /// Scene size, so that rays naming a triangle index >= n (parent_prim,
  /// expect.prim) are rejected from now on; -1 = unknown, skip that check.
  virtual void set_triangle_count(int32_t n) = 0;
  /// Threads that may parse rays ahead of next() (text traces parse each
  /// line's JSON; the other forms ignore it). next() returns the same rays and
  /// throws the same errors, in the same order, whatever the count.
  virtual void set_parse_threads(int threads) { (void)threads; }
  /// Path of the file, as given when opening it.
  virtual const std::string& path() const = 0;
  /// A TraceError located at the ray last returned by next(), for checks a
  /// caller makes later (e.g. a parent id that a replay cannot find).
  virtual TraceError error_at_last_ray(const std::string& field,
                                       const std::string& message) const = 0;
  /// Rays so far whose id could not be checked against every earlier id for a
  /// duplicate (trace_validation.h, TraceRayValidator::ids_not_checked).
  virtual int64_t ids_not_checked() const { return 0; }
};

class TraceSink {
 public:
  virtual ~TraceSink() = default;

  /// Appends one ray. Throws TraceError when the ray breaks the format's rules
  /// (the same rules the readers enforce) or cannot be written.
  virtual void write(const TraceRay& ray) = 0;
  /// Flushes and closes the file; throws TraceError on an I/O failure.
  /// The destructor closes too but swallows errors: call close() to see them.
  virtual void close() = 0;
  /// Path of the file being written.
  virtual const std::string& path() const = 0;
};

/// Opens the trace `path`, text or binary, as a TraceSource (declared here for
/// the user of a source; trace/trace_file.h, with the other operations on trace
/// files, documents it). Throws TraceError.
std::unique_ptr<TraceSource> open_trace(const std::string& path);

}  // namespace vbsim
