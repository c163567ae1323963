#include "hw/memory/zeroed_host_array.h"

#include <sys/mman.h>

#include <cstdlib>
#include <cstring>
#include <new>
#include <utility>

namespace vbsim::hw {

ZeroedHostArray::ZeroedHostArray(std::size_t bytes) : bytes_(bytes) {
  if (bytes == 0) return;
  if (bytes >= kMappedFromBytes) {
    // MAP_NORESERVE: address space, not memory, until a page is written.
    void* p = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    ::madvise(p, bytes, MADV_NOHUGEPAGE);  // a written way takes a page, not a 2 MiB huge page
    data_ = p;
    mapped_ = true;
    return;
  }
  const std::size_t rounded = (bytes + 63) / 64 * 64;  // aligned_alloc takes whole multiples of the alignment
  data_ = std::aligned_alloc(64, rounded);
  if (!data_) throw std::bad_alloc();
  std::memset(data_, 0, rounded);
}

ZeroedHostArray::~ZeroedHostArray() { release(); }

ZeroedHostArray::ZeroedHostArray(ZeroedHostArray&& o) noexcept
    : data_(std::exchange(o.data_, nullptr)), bytes_(std::exchange(o.bytes_, 0)), mapped_(std::exchange(o.mapped_, false)) {}

ZeroedHostArray& ZeroedHostArray::operator=(ZeroedHostArray&& o) noexcept {
  if (this != &o) {
    release();
    data_ = std::exchange(o.data_, nullptr);
    bytes_ = std::exchange(o.bytes_, 0);
    mapped_ = std::exchange(o.mapped_, false);
  }
  return *this;
}

void ZeroedHostArray::release() noexcept {
  if (!data_) return;
  if (mapped_) ::munmap(data_, bytes_);
  else std::free(data_);
  data_ = nullptr;
}

}  // namespace vbsim::hw
