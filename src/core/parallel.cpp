#include "asperity/core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cstdlib>
#include <exception>
#include <string_view>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::core {

namespace {

constexpr std::size_t kMaxWorkers = 256;

thread_local bool inside_item = false;

std::size_t read_worker_count() {
  if (const char* env = std::getenv("ASPERITY_THREADS")) {
    const std::string_view s(env);
    std::size_t v = 0;
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || p != s.data() + s.size() || v < 1 || v > kMaxWorkers) {
      throw InvalidInput(fmt::format(
          "environment variable ASPERITY_THREADS=\"{}\" is not allowed: an integer from 1 to {} "
          "(or unset: one thread per core)",
          printable(s), kMaxWorkers));
    }
    return v;
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

// 0 until the first worker_count() reads ASPERITY_THREADS or set_worker_count() sets it.
std::atomic<std::size_t> configured_workers{0};

}  // namespace

std::size_t worker_count() {
  std::size_t n = configured_workers.load(std::memory_order_relaxed);
  if (n == 0) {
    std::size_t expected = 0;
    n = read_worker_count();  // throws on a bad ASPERITY_THREADS, every time it is asked
    if (!configured_workers.compare_exchange_strong(expected, n, std::memory_order_relaxed)) {
      n = expected;  // set meanwhile by another thread
    }
  }
  return n;
}

void set_worker_count(std::size_t n) {
  if (n < 1 || n > kMaxWorkers) {
    throw InvalidInput(fmt::format("thread count {} is not allowed: 1 to {}", n, kMaxWorkers));
  }
  configured_workers.store(n, std::memory_order_relaxed);
}

void parallel_for(std::size_t n, const std::function<void(std::size_t)>& item) {
  if (n == 0) return;
  std::vector<std::exception_ptr> errors(n);
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    const bool was_inside = inside_item;
    inside_item = true;
    for (std::size_t i; (i = next.fetch_add(1, std::memory_order_relaxed)) < n;) {
      try {
        item(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
    inside_item = was_inside;
  };
  const std::size_t threads = inside_item ? 1 : std::min(worker_count(), n);
  {
    std::vector<std::jthread> team;
    team.reserve(threads - 1);
    for (std::size_t t = 1; t < threads; ++t) team.emplace_back(work);
    work();
  }  // joined
  for (const auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace asperity::core
