// A per-process cache of read-only values (fall states, hand-off state files): each value is
// made once per key and then shared by every env of every skill instance (each story of a
// batch builds its own skills). Internal to the task module.
#pragma once

#include <map>
#include <memory>
#include <mutex>

namespace sims::task {

/// The value `make()` gives for `key`, made on first use and shared read-only afterwards;
/// keys are per value type.
template <class Value, class Key, class Make>
std::shared_ptr<const Value> Cached(const Key& key, Make make) {
  static std::mutex mutex;
  static std::map<Key, std::shared_ptr<const Value>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[key];
  if (!slot) slot = std::make_shared<const Value>(make());
  return slot;
}

}  // namespace sims::task
