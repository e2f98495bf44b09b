#include "asperity/core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cstdlib>
#include <exception>
#include <string_view>
#include <thread>
#include <vector>

namespace asperity::core {

namespace {

thread_local bool inside_item = false;

std::size_t read_worker_count() {
  if (const char* env = std::getenv("ASPERITY_THREADS")) {
    const std::string_view s(env);
    std::size_t v = 0;
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec == std::errc() && p == s.data() + s.size() && v >= 1)
      return std::min<std::size_t>(v, 256);
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace

std::size_t worker_count() {
  static const std::size_t n = read_worker_count();
  return n;
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
