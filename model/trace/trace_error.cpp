#include "trace/trace_error.h"

#include <fmt/format.h>

namespace vbsim {

namespace {

std::string describe(const std::string& file, TraceError::Place place, int64_t line,
                     int64_t record, const std::string& field, const std::string& message) {
  std::string where;
  switch (place) {
    case TraceError::Place::File: where = fmt::format("{}: ", file); break;
    case TraceError::Place::Line: where = fmt::format("{}:{}: ", file, line); break;
    case TraceError::Place::Record: where = fmt::format("{}: record {}: ", file, record); break;
    case TraceError::Place::Header: where = fmt::format("{}: header: ", file); break;
  }
  if (!field.empty()) where += fmt::format("field '{}': ", field);
  return where + message;
}

}  // namespace

TraceError::TraceError(std::string file_, Place place_, int64_t line_, int64_t record_,
                       std::string field_, std::string message_)
    : std::runtime_error(describe(file_, place_, line_, record_, field_, message_)),
      file(std::move(file_)),
      place(place_),
      line(line_),
      record(record_),
      field(std::move(field_)),
      message(std::move(message_)) {}

TraceError TraceError::in_file(std::string file, std::string message) {
  return TraceError(std::move(file), Place::File, 0, -1, "", std::move(message));
}

TraceError TraceError::at_line(std::string file, int64_t line, std::string field,
                               std::string message) {
  return TraceError(std::move(file), Place::Line, line, -1, std::move(field), std::move(message));
}

TraceError TraceError::at_record(std::string file, int64_t record, std::string field,
                                 std::string message) {
  return TraceError(std::move(file), Place::Record, 0, record, std::move(field),
                    std::move(message));
}

TraceError TraceError::in_header(std::string file, std::string field, std::string message) {
  return TraceError(std::move(file), Place::Header, 0, -1, std::move(field), std::move(message));
}

}  // namespace vbsim
