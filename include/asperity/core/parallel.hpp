#pragma once
// Independent work items spread over the cores, with results that do not depend on the
// number of threads: each item writes its own slot, the caller combines the slots in
// index order afterwards, and when items throw, the exception of the lowest index is
// the one passed on (what a sequential loop would have thrown first).
#include <cstddef>
#include <functional>

namespace asperity::core {

/// Threads parallel_for() uses: the environment variable ASPERITY_THREADS when set
/// (an integer from 1 to 256; 1 runs everything on the calling thread; anything else
/// throws InvalidInput naming the variable), else the number of cores
/// (std::thread::hardware_concurrency, at least 1). Read once; set_worker_count()
/// overrides it for the whole process.
[[nodiscard]] std::size_t worker_count();

/// Sets the threads parallel_for() uses from now on (1 to 256; InvalidInput otherwise).
/// A process that already runs one item per core (a Dask worker in a sweep) sets 1, so
/// that the library does not start a second team of threads per core.
void set_worker_count(std::size_t n);

/// Calls item(i) for i in [0, n), on up to worker_count() threads (the caller is one of
/// them; items are handed out one at a time, so uneven items balance). Returns when all
/// items are done. Every item runs even if another throws; then the exception of the
/// lowest throwing index is rethrown. Called from inside an item, it runs sequentially
/// (no nested thread teams).
void parallel_for(std::size_t n, const std::function<void(std::size_t)>& item);

}  // namespace asperity::core
