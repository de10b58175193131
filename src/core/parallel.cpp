#include "sims/core/parallel.h"

#include <mutex>
#include <thread>
#include <vector>

#include <omp.h>

namespace sims {

namespace {
std::mutex& Mutex() {
  static std::mutex m;
  return m;
}
std::vector<std::function<void(int)>>& Listeners() {
  static std::vector<std::function<void(int)>> l;
  return l;
}
int& Current() {
  static int n = 0;
  return n;
}
}  // namespace

int HardwareThreads() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

int SetThreadCount(int threads) {
  const int n = threads > 0 ? threads : HardwareThreads();
  std::vector<std::function<void(int)>> listeners;
  {
    std::lock_guard<std::mutex> lock(Mutex());
    Current() = n;
    listeners = Listeners();
  }
  omp_set_num_threads(n);
  for (auto& l : listeners) l(n);
  return n;
}

int ThreadCount() {
  std::lock_guard<std::mutex> lock(Mutex());
  return Current() > 0 ? Current() : HardwareThreads();
}

void AddThreadCountListener(std::function<void(int)> listener) {
  int n;
  {
    std::lock_guard<std::mutex> lock(Mutex());
    Listeners().push_back(listener);
    n = Current() > 0 ? Current() : HardwareThreads();
  }
  listener(n);
}

}  // namespace sims
