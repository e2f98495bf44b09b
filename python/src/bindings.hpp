#pragma once
// One bind_<layer>() per layer of the library, each in its own file
// (python/src/<layer>.cpp); module.cpp calls them in layer order. To add a layer:
// declare its function here, define it in a new .cpp (CMake globs src/*.cpp) and call
// it from module.cpp. Use vectorize.hpp for functions of arrays.
#include <nanobind/nanobind.h>

namespace asperity::python {

namespace nb = nanobind;

/// Exceptions (asperity.Error, InvalidInput, NumericalError) and core/units.
void bind_core(nb::module_& m);
/// contact/: materials, normal and friction laws, Cattaneo-Mindlin, the four models.
void bind_contact(nb::module_& m);
/// surface/: profiles (read, level, filter), spectral moments, roughness parameters.
void bind_surface(nb::module_& m);

/// hysteresis/: backbones and the Masing engine.
void bind_hysteresis(nb::module_& m);
/// surface/rough_flat: the Greenwood-Williamson rough flat and its tabulated backbone.
void bind_rough_flat(nb::module_& m);
/// joint/: case files, predictions, fretting analysis, synthetic experiments, validation.
void bind_joint(nb::module_& m);
/// dynamics/: friction models, the single-DOF system of Eq. 7.1, simulate, analysis.
void bind_dynamics(nb::module_& m);
/// vibration/: structures, joint elements, harmonic balance, nonlinear modes, FRFs.
void bind_vibration(nb::module_& m);
/// vibration/: elements whose force law is a Python function (the _vibration submodule).
void bind_vibration_user(nb::module_& vibration);
/// vibration/: the 3-D rough-contact element and its shared surface (the _vibration submodule).
void bind_vibration_rough(nb::module_& vibration);
/// fem/ structures: asperity structure's steps and reduced-model files (fem_* functions).
void bind_fem_structure(nb::module_& m);
/// fem/: stiffness and consistent mass of quadratic solid elements (scipy.sparse).
void bind_fem(nb::module_& m);
/// The forwarders that give compiled functions and methods an inspect.Signature.
void bind_signatures(nb::module_& m);

/// For raw CPython entry points (python/src/hysteresis.cpp): the C++ exception being
/// handled, as the Python error nanobind's translators would set (call inside catch).
void set_python_error_from_current_exception();

}  // namespace asperity::python
