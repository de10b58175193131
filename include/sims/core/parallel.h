// One process-wide thread-count setting shared by the OpenMP environment loops and libtorch.
#pragma once

#include <functional>

namespace sims {

/// Sets the thread count (0 = all hardware threads) for OpenMP and every registered listener
/// (libtorch registers itself in the learning module). Returns the resolved count.
int SetThreadCount(int threads);

/// The resolved thread count (hardware threads until SetThreadCount is called).
int ThreadCount();

/// Number of hardware threads.
int HardwareThreads();

/// Calls `listener(n)` now and on every later SetThreadCount.
void AddThreadCountListener(std::function<void(int)> listener);

}  // namespace sims
