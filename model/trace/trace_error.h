// TraceError: the one exception every trace reader and writer throws for bad
// input or failed I/O. It names the file, where in the file (a 1-based text
// line, a 0-based binary record index, or the binary header) and the field.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>

namespace vbsim {

struct TraceError : std::runtime_error {
  /// Which part of the file the error points at.
  enum class Place : uint8_t { File, Line, Record, Header };

  std::string file;     ///< path of the trace file, as the caller gave it
  Place place = Place::File;
  int64_t line = 0;     ///< 1-based line of a text trace (Place::Line), else 0
  int64_t record = -1;  ///< 0-based record index of a binary file (Place::Record), else -1
  std::string field;    ///< the field at fault ("d", "expect.prim"), empty when none
  std::string message;  ///< what is wrong, without the location

  /// An error about the file as a whole: "path: message".
  static TraceError in_file(std::string file, std::string message);
  /// "path:12: field 'd': message" (field part omitted when empty).
  static TraceError at_line(std::string file, int64_t line, std::string field, std::string message);
  /// "path: record 12: field 'd': message"; record is the 0-based record index.
  static TraceError at_record(std::string file, int64_t record, std::string field,
                              std::string message);
  /// "path: header: field 'scene': message" (the JSON header of a binary file).
  static TraceError in_header(std::string file, std::string field, std::string message);

 private:
  TraceError(std::string file, Place place, int64_t line, int64_t record, std::string field,
             std::string message);
};

/// A problem with one field, before the reader knows where it is; readers turn
/// it into a TraceError with file and line/record. Internal to the trace layer.
struct TraceFieldProblem {
  std::string field;  ///< empty when the problem is not about one field
  std::string message;
};

}  // namespace vbsim
