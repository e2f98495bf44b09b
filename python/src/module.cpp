// The extension module asperity._core; the package python/asperity re-exports it.
#include <asperity/core/interrupt.hpp>

#include "bindings.hpp"

namespace {

// Python's main thread, the only one that runs signal handlers.
unsigned long g_main_thread = 0;

// Long C++ loops call this (core/interrupt.hpp) every 50 ms: with the GIL taken back,
// a pending Ctrl-C becomes KeyboardInterrupt, thrown through the C++ frames. Only on
// Python's main thread (signals are handled there only): a worker thread of the library
// never waits for the GIL, so a caller holding it cannot deadlock with its workers.
void raise_pending_signals() {
  if (!Py_IsInitialized() || PyThread_get_thread_ident() != g_main_thread) return;
  nanobind::gil_scoped_acquire acquire;
  if (PyErr_CheckSignals() != 0) throw nanobind::python_error();
}

}  // namespace

NB_MODULE(_core, m) {
  m.doc() =
      "asperity._core: bindings of the C++ library asperity (physics-based friction of "
      "bolted joints, Eriten 2012). Import `asperity` instead of this module. SI units "
      "throughout; const getters of C++ classes are read-only properties.";
  asperity::python::bind_core(m);
  asperity::python::bind_contact(m);
  asperity::python::bind_surface(m);
  asperity::python::bind_hysteresis(m);
  asperity::python::bind_rough_flat(m);
  asperity::python::bind_joint(m);
  asperity::python::bind_dynamics(m);
  asperity::python::bind_vibration(m);
  {
    auto vibration = nanobind::borrow<nanobind::module_>(m.attr("_vibration"));
    asperity::python::bind_vibration_user(vibration);
    asperity::python::bind_vibration_rough(vibration);
  }
  asperity::python::bind_fem_structure(m);
  asperity::python::bind_fem(m);
  asperity::python::bind_signatures(m);
  g_main_thread = nanobind::cast<unsigned long>(
      nanobind::module_::import_("threading").attr("main_thread")().attr("ident"));
  asperity::core::set_interrupt_hook(raise_pending_signals);
}
