#include "asperity/core/interrupt.hpp"

#include <atomic>
#include <chrono>

namespace asperity::core {

namespace {
std::atomic<InterruptHook> g_hook{nullptr};
}  // namespace

void set_interrupt_hook(InterruptHook hook) noexcept {
  g_hook.store(hook, std::memory_order_release);
}

void check_interrupt() {
  const InterruptHook hook = g_hook.load(std::memory_order_acquire);
  if (hook == nullptr) return;
  using Clock = std::chrono::steady_clock;
  thread_local Clock::time_point last = Clock::now();
  const auto now = Clock::now();
  if (now - last < std::chrono::milliseconds(50)) return;
  last = now;
  hook();
}

}  // namespace asperity::core
