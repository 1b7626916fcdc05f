// Runs fn(block) for block = 0 .. blockCount-1 on `threads` threads (work stealing by an
// atomic counter). Which thread runs a block never changes its result, so callers that
// write per-block outputs stay deterministic whatever the thread count.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace prt::bake {

// Threads to use when the user gives 0: every hardware thread.
inline unsigned defaultThreadCount() { return std::max(1u, std::thread::hardware_concurrency()); }

template <typename Fn>
void parallelFor(std::size_t blockCount, unsigned threads, Fn&& fn) {
  std::atomic<std::size_t> next{0};
  auto worker = [&](unsigned threadIndex) {
    for (std::size_t b = next.fetch_add(1); b < blockCount; b = next.fetch_add(1)) fn(b, threadIndex);
  };
  threads = std::max(1u, std::min<unsigned>(threads, static_cast<unsigned>(std::max<std::size_t>(1, blockCount))));
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker, t);
  worker(0);
  for (auto& th : pool) th.join();
}

}  // namespace prt::bake
