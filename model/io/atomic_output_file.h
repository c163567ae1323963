// AtomicOutputFile: an output file that appears under its name only once it is
// complete. It is written under a temporary name in the same directory
// ("NAME.partial-PID"), then flushed, closed and renamed over NAME by
// commit(), so that a failed, interrupted or killed run never leaves a file
// that looks whole, and an existing NAME stays intact until the new one is
// ready. Write errors (a full disk, /dev/full) surface as OutputError from
// write checks and commit(), never as a silent exit 0.
//
// A path naming an existing file that is not a regular file (/dev/null,
// /dev/stdout, a FIFO, a terminal) is written in place: there is nothing to
// rename, but commit() still reports write errors.
//
// Destroyed without commit(), the temporary is removed. While one is open,
// SIGINT and SIGTERM (unless the program handles them itself) remove the
// temporaries of every open AtomicOutputFile before the default action.
#pragma once
#include <fstream>
#include <stdexcept>
#include <string>

namespace vbsim {

/// An output that cannot be created or written: what() is "PATH: MESSAGE".
struct OutputError : std::runtime_error {
  OutputError(const std::string& path_, const std::string& message_)
      : std::runtime_error(path_ + ": " + message_), path(path_), message(message_) {}
  std::string path;
  std::string message;  ///< without the path, e.g. "write failed: No space left on device"
};

class AtomicOutputFile {
 public:
  /// Creates the temporary (or opens `path` in place, see above); binary mode
  /// when `binary`. Throws OutputError "PATH: cannot create: REASON".
  explicit AtomicOutputFile(std::string path, bool binary = false);
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  /// The stream to write to; valid until commit() or discard().
  std::ostream& stream() { return out_; }
  /// Throws OutputError "PATH: write failed: REASON" when a write has failed.
  void check() const;
  /// Flushes and closes the file and renames it to its name; a second call
  /// does nothing. Throws OutputError on any failure (the temporary is removed).
  void commit();
  /// Closes and removes the temporary (in-place outputs: just closes).
  void discard() noexcept;

  const std::string& path() const { return path_; }
  /// Where the bytes go until commit(): the temporary, or path() in place.
  const std::string& temp_path() const { return temp_; }
  bool committed() const { return done_ && committed_; }

 private:
  std::string path_, temp_;
  std::ofstream out_;
  int registry_slot_ = -1;  ///< slot in the signal-time cleanup list, -1: none
  bool in_place_ = false;
  bool done_ = false, committed_ = false;
};

/// Makes SIGINT and SIGTERM remove the temporaries of every open
/// AtomicOutputFile, print "vbsim: interrupted" on stderr and end the process
/// with `exit_code` (a program's own handler, installed later, takes over
/// while it is installed and gives this one back).
void exit_on_interrupt(int exit_code);

/// Writes `text` to `path` through an AtomicOutputFile; throws OutputError
/// naming `what` ("stats file") and the path.
void write_output_file(const std::string& path, const std::string& text, const char* what);

}  // namespace vbsim
