#include "capture/capture_trees.h"

#include <algorithm>
#include <cstring>

namespace vbsim::capture {

namespace {

/// A float's bits mapped so that unsigned order is numeric order (-0 < +0, NaNs last).
uint32_t ordered_bits(float x) {
  uint32_t b;
  std::memcpy(&b, &x, 4);
  return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
}

/// -1, 0, 1 comparing two rays' inputs.
int compare_inputs(const RawRay& a, const RawRay& b) {
  if (a.op != b.op) return a.op < b.op ? -1 : 1;
  const float* fa[] = {&a.org[0], &a.org[1], &a.org[2], &a.dir[0], &a.dir[1], &a.dir[2], &a.tnear, &a.tfar};
  const float* fb[] = {&b.org[0], &b.org[1], &b.org[2], &b.dir[0], &b.dir[1], &b.dir[2], &b.tnear, &b.tfar};
  for (int k = 0; k < 8; ++k) {
    const uint32_t x = ordered_bits(*fa[k]), y = ordered_bits(*fb[k]);
    if (x != y) return x < y ? -1 : 1;
  }
  return 0;
}

}  // namespace

void group_trees(uint32_t thread_index, ThreadRays& t, std::vector<TreeRef>& trees) {
  const std::size_t n = t.rays.size();
  std::vector<uint32_t> root(n, 0), count(n, 0), start(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!t.eligible[i]) continue;
    const int64_t p = t.links[i].parent;
    root[i] = p < 0 ? static_cast<uint32_t>(i) : root[static_cast<std::size_t>(p)];  // parents come first
    ++count[root[i]];
  }
  uint32_t next = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (t.eligible[i] && t.links[i].parent < 0) {
      start[i] = next;
      trees.push_back({thread_index, next, count[i]});
      next += count[i];
    }
  t.order.assign(next, 0);
  std::vector<uint32_t> fill = start;
  for (std::size_t i = 0; i < n; ++i)
    if (t.eligible[i]) t.order[fill[root[i]]++] = static_cast<uint32_t>(i);
}

void sort_trees(const std::vector<ThreadRays>& threads, std::vector<TreeRef>& trees) {
  auto ray = [&](const TreeRef& tr, uint32_t k) -> const RawRay& {
    const ThreadRays& t = threads[tr.thread];
    return t.rays[t.order[tr.first + k]];
  };
  std::sort(trees.begin(), trees.end(), [&](const TreeRef& a, const TreeRef& b) {
    const uint32_t n = std::min(a.count, b.count);
    for (uint32_t k = 0; k < n; ++k) {
      const int c = compare_inputs(ray(a, k), ray(b, k));
      if (c != 0) return c < 0;
    }
    return a.count < b.count;
  });
}

}  // namespace vbsim::capture
