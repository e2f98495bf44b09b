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

namespace asperity::core {

namespace {

constexpr std::size_t kMaxWorkers = 256;

thread_local bool inside_item = false;

std::size_t read_worker_count() {
  if (const char* env = std::getenv("ASPERITY_THREADS")) {
    const std::string_view s(env);
    std::size_t v = 0;
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec == std::errc() && p == s.data() + s.size() && v >= 1)
      return std::min<std::size_t>(v, kMaxWorkers);
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

std::atomic<std::size_t>& configured_worker_count() {
  static std::atomic<std::size_t> n{read_worker_count()};
  return n;
}

}  // namespace

std::size_t worker_count() { return configured_worker_count().load(std::memory_order_relaxed); }

void set_worker_count(std::size_t n) {
  if (n < 1 || n > kMaxWorkers) {
    throw InvalidInput(fmt::format("thread count {} is not allowed: 1 to {}", n, kMaxWorkers));
  }
  configured_worker_count().store(n, std::memory_order_relaxed);
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
