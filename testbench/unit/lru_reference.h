// An explicit LRU cache for cross-checks: each set is a list of lines, most
// recently used first. Slow on purpose and independent of hw/memory/lru_cache.h.
#pragma once
#include <cstdint>
#include <list>
#include <vector>

class ListLru {
 public:
  ListLru(uint32_t sets, uint32_t ways) : ways_(ways), sets_(sets) {}
  /// True on a hit (the line becomes most recent); a miss installs the line.
  bool access(uint64_t line) {
    std::list<uint64_t>& set = sets_[line % sets_.size()];
    for (auto it = set.begin(); it != set.end(); ++it)
      if (*it == line) {
        set.splice(set.begin(), set, it);
        return true;
      }
    set.push_front(line);
    if (set.size() > ways_) set.pop_back();
    return false;
  }

 private:
  size_t ways_;
  std::vector<std::list<uint64_t>> sets_;
};
