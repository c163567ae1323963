// ZeroedHostArray: a block of host memory that starts as zeros and takes host
// memory only where it is written. A large block is an anonymous mapping, whose
// pages the host supplies on their first write (a page only read reads zeros
// and takes none), so a cache's tag array sized for a cache far larger than the
// lines a run touches (memory.l1.size_bytes 2^31: 512 MiB of ways) costs host
// memory for the sets the run touches only. A small block is ordinary heap
// memory, cleared. Either way its start is aligned to 64 bytes.
#pragma once
#include <cstddef>

namespace vbsim::hw {

class ZeroedHostArray {
 public:
  /// Blocks from this size on are mapped, smaller ones come from the heap.
  static constexpr std::size_t kMappedFromBytes = std::size_t{1} << 20;

  /// `bytes` of zeros (0: an empty block). Throws std::bad_alloc when the
  /// host refuses the memory or the address space.
  explicit ZeroedHostArray(std::size_t bytes);
  ~ZeroedHostArray();
  ZeroedHostArray(ZeroedHostArray&& o) noexcept;
  ZeroedHostArray& operator=(ZeroedHostArray&& o) noexcept;
  ZeroedHostArray(const ZeroedHostArray&) = delete;
  ZeroedHostArray& operator=(const ZeroedHostArray&) = delete;

  void* data() const { return data_; }
  std::size_t bytes() const { return bytes_; }
  /// True when the block is a mapping whose pages come on first write.
  bool mapped() const { return mapped_; }

 private:
  void release() noexcept;

  void* data_ = nullptr;
  std::size_t bytes_ = 0;
  bool mapped_ = false;
};

}  // namespace vbsim::hw
