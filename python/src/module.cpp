// The extension module asperity._core; the package python/asperity re-exports it.
#include "bindings.hpp"

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
}
