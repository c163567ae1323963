#include "capture_output.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <pthread.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <vector>

#include "embree_library.h"
#include "filter_watch.h"

namespace vbsim::shim {

namespace {

using capture::RawApi;
using capture::RawRay;

constexpr std::size_t kBufferRecords = 4096;  // 384 KiB per tracing thread

/// One tracing thread's records. The owner locks `m` per record (uncontended);
/// the exit flush locks it too, so a late ray and the flush never interleave.
struct ThreadBuffer {
  std::mutex m;
  int fd = -1;
  int index = 0;
  std::size_t used = 0;
  bool closed = false;
  RawRay records[kBufferRecords];
};

struct Process {
  std::mutex m;  // guards `buffers`, `next_index` and the files
  std::mutex claim_m;  // guards `image` (taken after `m` when both are)
  std::string image;   // "<pid>.<g>" once claimed, else empty
  std::vector<ThreadBuffer*> buffers;
  int next_index = 0;
  std::string dir;
  bool enabled = false;
  std::atomic<bool> closing{false};
  std::atomic<bool> write_failed{false};
  long pid = 0;
  std::atomic<uint64_t> calls[2][capture::kRawApiCount] = {};
  std::atomic<uint64_t> rays[2][capture::kRawApiCount] = {};
  std::atomic<uint64_t> scenes{0}, commits{0};
  std::atomic<int> ray_masks{-1};  // RTC_DEVICE_PROPERTY_RAY_MASK_SUPPORTED once known, else -1
};

Process& process() {
  static Process* p = [] {
    auto* q = new Process;  // never destroyed: threads may still trace during exit
    const char* dir = std::getenv(capture::kCaptureDirEnv);
    q->enabled = dir && *dir;
    if (q->enabled) q->dir = dir;
    q->pid = static_cast<long>(::getpid());
    return q;
  }();
  return *p;
}

bool write_all(int fd, const void* data, std::size_t n) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t k = ::write(fd, p, n);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return false;
    p += k;
    n -= static_cast<std::size_t>(k);
  }
  return true;
}

/// Images of one pid tried before giving up (an exec chain, a reused pid).
constexpr unsigned kMaxImagesPerPid = 1u << 16;

/// This image's name, claimed on first use: <pid>.<g> with the first g for
/// which process-<pid>.<g>.txt can be created anew (O_EXCL). An exec'd image
/// keeps the pid but not the memory, so it claims the next g; a forked child,
/// or a later process given a reused pid, claims its own too. Nothing of one
/// image ever writes over another's files.
std::string claimed_image() {
  Process& p = process();
  std::lock_guard<std::mutex> lock(p.claim_m);
  if (!p.image.empty()) return p.image;
  for (unsigned g = 0; g < kMaxImagesPerPid; ++g) {
    const std::string image = std::to_string(p.pid) + "." + std::to_string(g);
    const std::string path = p.dir + "/process-" + image + ".txt";
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd >= 0) {
      ::close(fd);
      return p.image = image;
    }
    if (errno != EEXIST) break;
  }
  p.write_failed = true;  // the directory cannot be written: nothing will be
  return p.image = std::to_string(p.pid) + ".0";
}

int create_file(const std::string& name) {
  const std::string path = process().dir + "/" + name;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) process().write_failed = true;
  return fd;
}

/// Writes the buffered records of `b` (its mutex held).
void flush_locked(ThreadBuffer& b) {
  if (b.used == 0) return;
  if (b.fd < 0 || !write_all(b.fd, b.records, b.used * sizeof(RawRay))) process().write_failed = true;
  b.used = 0;
}

void close_locked(ThreadBuffer& b) {
  flush_locked(b);
  if (b.fd >= 0) ::close(b.fd);
  b.fd = -1;
  b.closed = true;
}

ThreadBuffer* new_buffer() {
  Process& p = process();
  auto* b = new ThreadBuffer;
  std::lock_guard<std::mutex> lock(p.m);
  b->index = p.next_index++;
  b->fd = create_file("rays-" + claimed_image() + "-" + std::to_string(b->index) + ".bin");
  p.buffers.push_back(b);
  return b;
}

/// The calling thread's buffer, released (flushed, closed, freed) at thread exit.
struct ThreadSlot {
  ThreadBuffer* buffer = nullptr;
  ~ThreadSlot() {
    if (!buffer) return;
    Process& p = process();
    std::lock_guard<std::mutex> lock(p.m);
    for (auto it = p.buffers.begin(); it != p.buffers.end(); ++it)
      if (*it == buffer) {
        {
          std::lock_guard<std::mutex> bl(buffer->m);
          close_locked(*buffer);
        }
        p.buffers.erase(it);
        delete buffer;
        break;
      }
    buffer = nullptr;
  }
};
thread_local ThreadSlot t_slot;

/// `before_exec`: the image is about to be replaced (ended_by_exec 1).
void write_summary(bool before_exec) {
  Process& p = process();
  std::string s = "pid " + std::to_string(p.pid) + "\n";
  for (int op = 0; op < 2; ++op)
    for (int api = 0; api < capture::kRawApiCount; ++api) {
      const char* name = capture::raw_api_name(static_cast<RawApi>(api), op == 1);
      s += std::string("calls.") + name + " " + std::to_string(p.calls[op][api].load()) + "\n";
      s += std::string("rays.") + name + " " + std::to_string(p.rays[op][api].load()) + "\n";
    }
  s += "threads " + std::to_string(p.next_index) + "\n";
  s += "scenes " + std::to_string(p.scenes.load()) + "\n";
  s += "commits " + std::to_string(p.commits.load()) + "\n";
  s += std::string("write_failed ") + (p.write_failed ? "1" : "0") + "\n";
  // A shared libembree3 in the program's namespace, linked or dlopened: what the interposed
  // functions call (absent when the program links Embree statically or not at all).
  s += std::string("embree_loaded ") + (embree_loaded() ? "1" : "0") + "\n";
  if (p.ray_masks.load() >= 0) s += "ray_mask_supported " + std::to_string(p.ray_masks.load()) + "\n";
  s += "unwatched_filter_functions " + std::to_string(unwatched_filter_functions()) + "\n";
  s += std::string("ended_by_exec ") + (before_exec ? "1" : "0") + "\n";
  s += "complete 1\n";
  write_capture_file("process-" + claimed_image() + ".txt", s);
}

/// At process exit (after atexit handlers and the main thread's thread-local
/// destructors): flush every thread still registered, then the summary.
__attribute__((destructor)) void finish_capture() {
  Process& p = process();
  if (!p.enabled || p.closing.exchange(true)) return;
  {
    std::lock_guard<std::mutex> lock(p.m);
    for (ThreadBuffer* b : p.buffers) {
      std::lock_guard<std::mutex> bl(b->m);
      close_locked(*b);
    }
  }
  // An Embree the shim never saw (dlmopen) may have traced: the capture is not whole.
  const std::string out_of_reach = embree_out_of_reach();
  if (!out_of_reach.empty()) write_capture_file("refused-" + claimed_image() + ".txt", out_of_reach + "\n");
  write_summary(false);
}

// fork(): the child keeps only the forking thread. It must not write the
// parent's buffered records again, so it drops every buffer and starts afresh
// under its own pid and image name.
void before_fork() {
  process().m.lock();
  process().claim_m.lock();
}
void after_fork_parent() {
  process().claim_m.unlock();
  process().m.unlock();
}
void after_fork_child() {
  Process& p = process();
  p.buffers.clear();  // the parent's buffers: abandoned, never written from here
  p.next_index = 0;
  p.pid = static_cast<long>(::getpid());
  p.image.clear();  // claimed when the child first writes
  for (auto& op : p.calls)
    for (auto& c : op) c = 0;
  for (auto& op : p.rays)
    for (auto& c : op) c = 0;
  p.scenes = 0;
  p.commits = 0;
  t_slot.buffer = nullptr;
  p.claim_m.unlock();
  p.m.unlock();
}

__attribute__((constructor)) void start_capture() {
  if (process().enabled) pthread_atfork(before_fork, after_fork_parent, after_fork_child);
}

}  // namespace

bool capture_enabled() {
  const Process& p = process();
  return p.enabled && !p.closing.load(std::memory_order_relaxed);
}

void record_ray(const capture::RawRay& ray) {
  ThreadBuffer* b = t_slot.buffer;
  if (!b) b = t_slot.buffer = new_buffer();
  std::lock_guard<std::mutex> lock(b->m);
  if (b->closed) return;  // the process is exiting
  b->records[b->used++] = ray;
  process().rays[ray.op == static_cast<uint16_t>(capture::RawOp::Occluded)][ray.api].fetch_add(1, std::memory_order_relaxed);
  if (b->used == kBufferRecords) flush_locked(*b);
}

void count_call(capture::RawApi api, bool occluded) {
  process().calls[occluded][static_cast<int>(api)].fetch_add(1, std::memory_order_relaxed);
}

void write_capture_file(const std::string& name, const std::string& bytes) {
  Process& p = process();
  const int fd = create_file(name);
  if (fd < 0) return;
  if (!write_all(fd, bytes.data(), bytes.size())) p.write_failed = true;
  ::close(fd);
}

std::string capture_image() { return claimed_image(); }

void prepare_for_exec() {
  Process& p = process();
  // A vfork() child runs in its parent's memory (no fork handler ran, so the
  // pid differs): the parent's buffers and summary are not its to write.
  if (!p.enabled || p.closing.load() || static_cast<long>(::getpid()) != p.pid) return;
  {
    std::lock_guard<std::mutex> lock(p.m);
    for (ThreadBuffer* b : p.buffers) {
      std::lock_guard<std::mutex> bl(b->m);
      flush_locked(*b);  // the files stay open: a failed exec goes on writing them
    }
  }
  write_summary(true);
}
void refuse_capture(const std::string& why) {
  Process& p = process();
  if (p.enabled && !p.closing.exchange(true)) write_capture_file("refused-" + claimed_image() + ".txt", why + "\n");
  const std::string line = "vbsim capture shim: " + why + "\n";
  (void)!::write(2, line.data(), line.size());
  ::_exit(capture::kShimRefusedStatus);
}

void note_ray_masks(bool supported) { process().ray_masks.store(supported ? 1 : 0); }

void count_scene() { process().scenes.fetch_add(1); }
void count_commit() { process().commits.fetch_add(1); }

}  // namespace vbsim::shim
