#pragma once
// Cooperative interruption of long computations. The library's long loops (the time
// integration, Masing histories, the load cases of a prediction) call
// check_interrupt() every so often; a front end may install a hook that throws to
// abandon the computation (the Python bindings: KeyboardInterrupt on Ctrl-C, checked
// with PyErr_CheckSignals). Without a hook check_interrupt() does nothing.
namespace asperity::core {

/// Called by check_interrupt() at most every 50 ms of wall time per thread; may throw.
using InterruptHook = void (*)();

/// Installs (or, with nullptr, removes) the process-wide hook.
void set_interrupt_hook(InterruptHook hook) noexcept;

/// Calls the hook when one is installed and 50 ms have passed since this thread last
/// called it. Costs a clock read when a hook is installed, an atomic load otherwise.
void check_interrupt();

}  // namespace asperity::core
