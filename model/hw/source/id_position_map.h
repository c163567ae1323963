// IdPositionMap: ray id -> trace position for the rays a ray source remembers
// (at most `capacity` at once): open addressing with linear probing in a
// power-of-two table at most half full (16 bytes a slot), and backward-shift
// deletion (no tombstones), so lookups stay short however long the trace. The
// table starts small and doubles as ids arrive, up to what `capacity` ids need,
// then allocates no more.
#pragma once
#include <cstdint>
#include <vector>

namespace vbsim::hw {

class IdPositionMap {
 public:
  explicit IdPositionMap(uint32_t capacity) {
    size_t size = 16;
    while (size < 2 * size_t{capacity} && size < kFirstSize) size *= 2;
    slots_.assign(size, Slot{});
    mask_ = size - 1;
  }

  /// Sets `id`'s position (the map holds fewer than `capacity` ids).
  void set(int64_t id, uint64_t pos) {
    if (2 * (count_ + 1) > slots_.size()) grow();
    size_t i = home(id);
    while (used(i) && slots_[i].id != id) i = (i + 1) & mask_;
    count_ += used(i) ? 0 : 1;
    slots_[i] = {id, pos};
  }
  /// The position of `id`, or false.
  bool find(int64_t id, uint64_t& pos) const {
    for (size_t i = home(id); used(i); i = (i + 1) & mask_)
      if (slots_[i].id == id) {
        pos = slots_[i].pos;
        return true;
      }
    return false;
  }
  /// Forgets `id` when it is at position `pos` (a later ray with the same id stays).
  void erase(int64_t id, uint64_t pos) {
    size_t i = home(id);
    while (used(i) && !(slots_[i].id == id && slots_[i].pos == pos)) i = (i + 1) & mask_;
    if (!used(i)) return;
    // Backward shift: move later entries of the probe run into the hole when their home allows.
    for (size_t hole = i, j = (i + 1) & mask_;; j = (j + 1) & mask_) {
      if (!used(j)) {
        slots_[hole].pos = kEmpty;
        --count_;
        return;
      }
      const size_t h = home(slots_[j].id);
      const bool movable = hole <= j ? (h <= hole || h > j) : (h <= hole && h > j);
      if (movable) {
        slots_[hole] = slots_[j];
        hole = j;
      }
    }
  }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t{0};  ///< the position of an unused slot
  static constexpr size_t kFirstSize = size_t{1} << 12;
  struct Slot {
    int64_t id = 0;
    uint64_t pos = kEmpty;
  };
  bool used(size_t i) const { return slots_[i].pos != kEmpty; }
  size_t home(int64_t id) const {
    uint64_t x = static_cast<uint64_t>(id) * 0x9E3779B97F4A7C15ull;  // Fibonacci hashing
    return static_cast<size_t>(x >> 20) & mask_;
  }
  /// Twice the table, every id rehashed.
  void grow() {
    std::vector<Slot> old(slots_.size() * 2, Slot{});
    old.swap(slots_);
    mask_ = slots_.size() - 1;
    for (const Slot& s : old)
      if (s.pos != kEmpty) {
        size_t i = home(s.id);
        while (used(i)) i = (i + 1) & mask_;
        slots_[i] = s;
      }
  }

  std::vector<Slot> slots_;
  size_t mask_;
  size_t count_ = 0;
};

}  // namespace vbsim::hw
