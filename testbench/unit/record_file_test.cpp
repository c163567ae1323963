// Files of fixed-size records after a prefix, as the binary trace and rtcore
// ray readers and writers stream them: records across buffer refills, a
// partial last record found from the size or by reading, an empty payload,
// read and create errors, and the writer's bytes.
#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <string>

#include "trace/record_file_reader.h"
#include "trace/record_file_writer.h"
#include "trace_test_support.h"

using namespace vbsim;
using namespace vbsim::test;

namespace {

/// `count` records of `record_bytes` bytes; byte j of record k is 10 k + j.
std::string numbered_records(int count, std::size_t record_bytes) {
  std::string bytes;
  for (int k = 0; k < count; ++k)
    for (std::size_t j = 0; j < record_bytes; ++j) bytes.push_back(static_cast<char>(10 * k + j));
  return bytes;
}

/// A reader of `path` past a prefix of `prefix_bytes` bytes, which it skips by reading.
RecordFileReader reader_after_prefix(const std::string& path, std::size_t prefix_bytes,
                                     RecordFileShape shape) {
  std::ifstream in = RecordFileReader::open_file(path);
  std::string prefix(prefix_bytes, '\0');
  in.read(prefix.data(), static_cast<std::streamsize>(prefix_bytes));
  REQUIRE(static_cast<std::size_t>(in.gcount()) == prefix_bytes);
  return RecordFileReader(path, std::move(in), prefix_bytes, std::move(shape));
}

}  // namespace

TEST_CASE("record file: records after a prefix stream across buffer refills", "[trace]") {
  TempDir dir("record-file-refill");
  const std::string path = dir.file("r.bin");
  // 3 records per read: 9 records fill the buffer exactly three times, 10 leave one over.
  const int count = GENERATE(9, 10);
  write_file(path, "HDR!xyz" + numbered_records(count, 5));
  RecordFileReader reader = reader_after_prefix(path, 7, {5, 3, ""});
  CHECK(reader.record_count() == count);
  const uint8_t* first = nullptr;
  for (int k = 0; k < count; ++k) {
    const uint8_t* record = reader.next();
    REQUIRE(record != nullptr);
    CHECK(reader.records_read() == k + 1);
    for (int j = 0; j < 5; ++j) CHECK(record[j] == 10 * k + j);
    // Every read lands in the one buffer: record 3k sits where record 0 did.
    if (k == 0) first = record;
    if (k % 3 == 0) CHECK(record == first);
  }
  CHECK(reader.next() == nullptr);
  CHECK(reader.next() == nullptr);
  CHECK(reader.records_read() == count);
}

TEST_CASE("record file: a size that leaves a partial last record fails on opening", "[trace]") {
  TempDir dir("record-file-partial-size");
  const std::string path = dir.file("r.bin");
  write_file(path, "abc" + numbered_records(4, 6) + std::string(4, 'x'));
  TraceError e = trace_error_of([&] { reader_after_prefix(path, 3, {6, 2, "six bytes: a b c d e f"}); });
  CHECK(e.place == TraceError::Place::Record);
  CHECK(e.record == 4);
  CHECK(e.field.empty());
  CHECK(e.message ==
        "truncated: the file ends 4 bytes into this 6-byte record (six bytes: a b c d e f)");
  CHECK(std::string(e.what()) == path + ": record 4: " + e.message);

  // Without a layout the message ends at the record size.
  e = trace_error_of([&] { reader_after_prefix(path, 3, {6, 2, ""}); });
  CHECK(e.message == "truncated: the file ends 4 bytes into this 6-byte record");
}

TEST_CASE("record file: a partial last record met while reading names its index", "[trace]") {
  TempDir dir("record-file-partial-read");
  const std::string path = dir.file("r.bin");
  const std::size_t per_read = GENERATE(1, 4);
  write_file(path, numbered_records(2, 8));
  RecordFileReader reader = reader_after_prefix(path, 0, {8, per_read, ""});
  CHECK(reader.record_count() == 2);
  // The file grows by a partial record after the size check, as a pipe's
  // stream would end: only the read can find it.
  {
    std::ofstream grow(path, std::ios::binary | std::ios::app);
    grow.write("12345", 5);
  }
  for (int k = 0; k < 2; ++k) {
    const uint8_t* record = reader.next();
    REQUIRE(record != nullptr);
    CHECK(record[7] == 10 * k + 7);
  }
  TraceError e = trace_error_of([&] { reader.next(); });
  CHECK(e.record == 2);
  CHECK(e.message == "truncated: the file ends 5 bytes into this 8-byte record");
}

TEST_CASE("record file: an empty payload has no records", "[trace]") {
  TempDir dir("record-file-empty");
  const std::string path = dir.file("r.bin");
  const std::size_t prefix_bytes = GENERATE(0, 16);
  write_file(path, std::string(prefix_bytes, 'p'));
  RecordFileReader reader = reader_after_prefix(path, prefix_bytes, {28, 4, ""});
  CHECK(reader.record_count() == 0);
  CHECK(reader.next() == nullptr);
  CHECK(reader.records_read() == 0);

  RecordFileReader none;
  CHECK(none.next() == nullptr);
}

TEST_CASE("record file: open and read errors name the file", "[trace]") {
  TempDir dir("record-file-errors");
  TraceError e = trace_error_of([&] { RecordFileReader::open_file(dir.file("missing.bin")); });
  CHECK(e.place == TraceError::Place::File);
  CHECK_THAT(e.message, Catch::StartsWith("cannot open: "));

  // A directory opens, has no file size, and fails on the first read.
  const std::string sub = dir.file("sub");
  std::filesystem::create_directories(sub);
  RecordFileReader reader = reader_after_prefix(sub, 0, {4, 2, ""});
  CHECK(reader.record_count() == -1);
  e = trace_error_of([&] { reader.next(); });
  CHECK(std::string(e.what()) == sub + ": record 0: read error");
}

TEST_CASE("record file writer: prefix, then records across buffer flushes", "[trace]") {
  TempDir dir("record-file-writer");
  const std::string path = dir.file("w.bin");
  const int count = GENERATE(4, 5);  // 2 records per write: exact flushes, or one left for close
  {
    RecordFileWriter writer(path, 3, 2, "PRE");
    for (int k = 0; k < count; ++k) {
      CHECK(writer.records_written() == k);
      writer.append([&](uint8_t* record) {
        for (int j = 0; j < 3; ++j) record[j] = static_cast<uint8_t>(10 * k + j);
      });
    }
    CHECK(writer.records_written() == count);
    writer.close();
    writer.close();  // a second close does nothing
    TraceError e = trace_error_of([&] { writer.require_open(); });
    CHECK(std::string(e.what()) == path + ": write after close");
  }
  CHECK(read_file(path) == "PRE" + numbered_records(count, 3));
}

TEST_CASE("record file writer: without close() no file appears", "[trace]") {
  TempDir dir("record-file-writer-dtor");
  const std::string path = dir.file("w.bin");
  write_file(path, "previous");
  {
    RecordFileWriter writer(path, 2, 1);  // a record per write: bytes reach the temporary at once
    writer.append([](uint8_t* record) {
      record[0] = 'o';
      record[1] = 'k';
    });
    CHECK(read_file(path) == "previous");  // written under a temporary name until close()
  }
  CHECK(read_file(path) == "previous");  // a writer that never closed replaces nothing
  CHECK(std::distance(std::filesystem::directory_iterator(std::filesystem::path(path).parent_path()),
                      std::filesystem::directory_iterator{}) == 1);  // and leaves no temporary

  TraceError e = trace_error_of([&] { RecordFileWriter w(dir.file("no/such/dir/w.bin"), 2, 8); });
  CHECK(e.place == TraceError::Place::File);
  CHECK_THAT(e.message, Catch::StartsWith("cannot create: "));
}
