// The last few values computed on this thread, by key: a round of consumer checks asks the same
// exact facts of one matrix from several judges (the inverse of M' by the depth, world and
// corners judges), and a shader's batch asks many pixels of one matrix. Internal to the oracle
// library.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <utility>

namespace oblique::oracle {

/// Holds the values of the last N keys asked; a value is handed out by shared_ptr, so a caller's
/// outlives its slot's reuse. Keys compare with ==; one that never equals itself (a NaN in it) is
/// computed each time, which costs time, never a wrong value. One per thread (thread_local).
template <class Key, class Value, std::size_t N = 8>
class Recent {
 public:
  /// The value for `key`: kept, or make() (then kept in the oldest slot).
  template <class Make>
  std::shared_ptr<const Value> get(const Key& key, Make&& make) {
    for (const auto& [k, v] : slots_)
      if (v && k == key) return v;
    auto& slot = slots_[next_];
    next_ = (next_ + 1) % N;
    slot.second.reset();  // a make() that throws leaves the slot empty, never stale
    slot.first = key;
    slot.second = std::make_shared<const Value>(make());
    return slot.second;
  }

 private:
  std::array<std::pair<Key, std::shared_ptr<const Value>>, N> slots_{};
  std::size_t next_ = 0;
};

}  // namespace oblique::oracle
