// parallel_for: job(i) for every i in [0, n) on up to `threads` threads (the
// caller's thread included), indices handed out in ascending order. A job that
// throws stops the handing out of further indices; once every thread has
// joined, the exception of the lowest index that threw is rethrown. Every
// index below it was handed out before it and ran to its end, so the error is
// the one a loop over i in order would have met first, whatever the thread
// count.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace vbsim {

template <class Job>
void parallel_for(size_t n, int threads, Job job) {
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex error_mutex;
  std::exception_ptr error;
  size_t error_index = n;
  auto worker = [&] {
    for (size_t i; !failed.load() && (i = next.fetch_add(1)) < n;) {
      try {
        job(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (i < error_index) error_index = i, error = std::current_exception();
        failed.store(true);
      }
    }
  };
  const size_t extra = n == 0 ? 0 : std::min<size_t>(n, static_cast<size_t>(std::max(threads, 1))) - 1;
  std::vector<std::thread> pool;
  for (size_t t = 0; t < extra; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

/// Chunks of `chunk_size` consecutive indices that cover [0, n).
inline size_t chunk_count(size_t n, size_t chunk_size) { return (n + chunk_size - 1) / chunk_size; }

/// job(chunk, begin, end) for every chunk of `chunk_size` consecutive indices
/// of [0, n) (the last one shorter), the chunks handed out as parallel_for
/// hands out indices, with its rule for errors.
template <class Job>
void parallel_for_chunks(size_t n, size_t chunk_size, int threads, Job job) {
  parallel_for(chunk_count(n, chunk_size), threads,
               [&](size_t c) { job(c, c * chunk_size, std::min(n, (c + 1) * chunk_size)); });
}

}  // namespace vbsim
