// AtomicOutputFile: an output file that appears under its name only once it is
// complete. It is written under a temporary name in the same directory
// ("NAME.partial-PID-N"), then flushed, closed and renamed over NAME by
// commit(), so that a failed, interrupted or killed run never leaves a file
// that looks whole, and an existing NAME stays intact until the new one is
// ready. Write errors (a full disk, /dev/full) surface as OutputError from
// write checks and commit(), never as a silent exit 0.
//
// A path naming an existing file that is not a regular file (/dev/null,
// /dev/stdout, a FIFO, a terminal) is written in place: there is nothing to
// rename, but commit() still reports write errors.
//
// Before creating its temporary it removes the temporaries of the same NAME
// that runs killed with SIGKILL left (their process no longer runs:
// io/stale_temporaries.h).
//
// Destroyed without commit(), the temporary is removed. While one is open,
// SIGINT and SIGTERM (unless the program handles them itself) remove the
// temporaries of every open AtomicOutputFile before the default action.
//
// Held commits (hold_output_commits): a program whose run also writes data to
// standard output holds the renames until it knows that data arrived. While
// commits are held, commit() finishes the file (flush, close, every write
// check) but leaves it under its temporary name; commit_held_outputs() then
// renames them all, in the order commit() was called, and
// discard_held_outputs() removes them. A held file stays on the signal-time
// cleanup list until it is renamed or removed; finished_output_path() names it
// for a run that reads its own output back.
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

/// From now on, commit() holds the rename (see the top of this file).
void hold_output_commits();
/// Renames every held output to its name, in the order of their commit(),
/// and stops holding. Throws OutputError naming the first output that cannot
/// be renamed; that one and the rest are removed.
void commit_held_outputs();
/// Removes every held output's temporary and stops holding.
void discard_held_outputs() noexcept;
/// Where the finished content of the output `path` can be read now: the
/// temporary of its latest held commit while that is held, else `path` (for
/// an output a run rewrites, such as a VCD given its provenance comment).
std::string finished_output_path(const std::string& path);

/// While one exists, commit() renames at once even when commits are held: for
/// the outputs a run reads back before it ends (gen's scenes, read again to
/// compute their traces). Not for use from several threads at once.
class CommitsAtOnce {
 public:
  CommitsAtOnce();
  ~CommitsAtOnce();
  CommitsAtOnce(const CommitsAtOnce&) = delete;
  CommitsAtOnce& operator=(const CommitsAtOnce&) = delete;

 private:
  bool was_holding_;
};

/// Writes `text` to `path` through an AtomicOutputFile; throws OutputError
/// naming `what` ("stats file") and the path.
void write_output_file(const std::string& path, const std::string& text, const char* what);

}  // namespace vbsim
