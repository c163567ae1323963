// The memory system's boundary: what every part of hw/memory/ implements and
// what it is reached through (docs/memory-model.md).
//
// Part contract (hw/memory/): the memory answers *when* a core's reads of the
// BVH (nodes, triangles, stack spill areas) have their data; it never computes
// a hit, so no change here can change one. It is called by the ray-test cores'
// memory ports (MemoryReadIf: the scheduler, hw/scheduler/, calls a core's
// L1 or ideal memory while handling a slot's step) and by the accelerator's
// memory step (hw/memory/memory_clock.h: misses sent in time order). It may
// call only downwards (L1 -> L2 through LineReadIf, L2 -> DRAM through the
// TLM-2.0 socket) and back up through the answer interfaces (LineFillIf,
// ReadDoneIf) for reads it answered kPendingCycle. Its configuration is
// hw/memory/memory_config.h (the `memory` object), its addresses
// hw/memory/bvh_address_map.h. Replacing a level: AcceleratorUnits
// (hw/accelerator_units.h) for an L1 or the L2, the TLM-2.0 socket
// (Accelerator::memory_socket) for the DRAM.
#pragma once
#include <cstdint>

#include <systemc>

#include "hw/pending_cycle.h"

namespace vbsim::hw {

/// A core's reads of the BVH (nodes, triangles, its slots' stack spill areas),
/// answered by its L1 cache or by an ideal memory.
class MemoryReadIf : public virtual sc_core::sc_interface {
 public:
  /// A read of `bytes` at byte address `addr` issued at cycle `now` for slot
  /// `slot` (the core's index of it): the cycle its data are there (>= now + 1),
  /// or kPendingCycle, and then the memory calls ReadDoneIf::read_done(slot,
  /// cycle) of the same core later (approximately timed memory only).
  virtual uint64_t read(uint64_t addr, uint32_t bytes, uint64_t now, uint32_t slot) = 0;
};

/// The core's side of a pending read.
class ReadDoneIf : public virtual sc_core::sc_interface {
 public:
  /// The read of slot `slot` that was answered kPendingCycle has its data at
  /// `ready` (not before the cycle being handled).
  virtual void read_done(uint32_t slot, uint64_t ready) = 0;
};

/// An L1's misses, to the shared L2: one cache line each.
class LineReadIf : public virtual sc_core::sc_interface {
 public:
  /// Line `line` (byte address / line size) asked for at cycle `t` by the L1 of
  /// core `core`: the cycle it arrives there, or kPendingCycle, and then the L2
  /// calls LineFillIf::line_filled(line, cycle) of that core's L1 later.
  virtual uint64_t read_line(uint64_t line, uint64_t t, uint32_t core) = 0;
};

/// The L1's side of a pending line.
class LineFillIf : public virtual sc_core::sc_interface {
 public:
  virtual void line_filled(uint64_t line, uint64_t fill) = 0;
};

/// What a replacement L1 (AcceleratorUnits::l1_cache) implements besides
/// MemoryReadIf to be wired as the built-in L1 is: with the cache hierarchy,
/// the accelerator binds next_level() to the shared L2's LineReadIf (misses go
/// on to the L2) and gives the L2 fill_target() for the lines it answers
/// kPendingCycle; the core binds read_done() to its ReadDoneIf (the answers to
/// the core's reads the replacement answered kPendingCycle). With an ideal
/// memory there is no L2 and next_level() stays unbound (declare it
/// sc_port<LineReadIf, 1, SC_ZERO_OR_MORE_BOUND> to allow that). A replacement
/// without it is the core's whole memory path (it does not reach the L2).
class L2ClientIf {
 public:
  virtual ~L2ClientIf() = default;
  virtual sc_core::sc_port_b<LineReadIf>& next_level() = 0;
  virtual LineFillIf& fill_target() = 0;
  virtual sc_core::sc_port_b<ReadDoneIf>& read_done() = 0;
};

}  // namespace vbsim::hw
