// hysteresis/: the Masing engine over any backbone (numpy histories in and out).
#include <nanobind/ndarray.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/shared_ptr.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/hysteresis/masing.hpp"
#include "bindings.hpp"
#include "vectorize.hpp"

#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#include <numpy/arrayobject.h>

namespace asperity::python {

using namespace nb::literals;
using namespace asperity::hysteresis;

namespace {

// numpy's C API, imported on first use (this file is its only user).
void import_numpy() {
  static const bool imported = [] {
    if (_import_array() < 0) throw nb::python_error();
    return true;
  }();
  (void)imported;
}

// Forces (displacements with `inverse`) along a history from the current state of
// `h`, which is not changed. A Python float gives a float; a 1-D float64 numpy array
// (any stride) is read in place and the result written straight into a new array made
// by numpy's C API (a small call costs about a Python call; numpy.empty from Python
// alone costs 4 of them); anything else goes through numpy.asarray first.
nb::object along_history(const Hysteresis& h, const ArrayLike& in, bool inverse) {
  double v = 0.0;
  if (detail::python_number(in.obj, v)) {
    if (!inverse) return nb::float_(h.peek(v));
    Hysteresis c = h;
    return nb::float_(c.update_force(v));
  }
  import_numpy();
  nb::object source = in.obj;
  auto usable = [](PyObject* o) {
    if (!PyArray_Check(o)) return false;
    auto* a = reinterpret_cast<PyArrayObject*>(o);
    return PyArray_NDIM(a) == 1 && PyArray_TYPE(a) == NPY_DOUBLE && PyArray_ISBEHAVED_RO(a);
  };
  if (!usable(source.ptr())) {
    nb::module_ np = nb::module_::import_("numpy");
    source = np.attr("ascontiguousarray")(np.attr("asarray")(in.obj, nb::arg("dtype") = "float64"));
    if (!usable(source.ptr())) {
      throw InvalidInput(fmt::format(
          "{} must be a 1-D sequence, got an array with {} dimensions",
          inverse ? "the force history" : "the displacement history",
          PyArray_Check(source.ptr()) ? PyArray_NDIM(reinterpret_cast<PyArrayObject*>(source.ptr()))
                                      : 0));
    }
  }
  auto* a = reinterpret_cast<PyArrayObject*>(source.ptr());
  npy_intp n = PyArray_DIM(a, 0);
  const npy_intp stride = PyArray_STRIDE(a, 0);
  const char* x = static_cast<const char*>(PyArray_DATA(a));
  nb::object result = nb::steal(PyArray_SimpleNew(1, &n, NPY_DOUBLE));
  if (!result.is_valid()) throw nb::python_error();
  auto* out = static_cast<double*>(PyArray_DATA(reinterpret_cast<PyArrayObject*>(result.ptr())));
  if (n == 1 && !inverse) {
    double x0 = 0.0;
    std::memcpy(&x0, x, sizeof x0);
    out[0] = h.peek(x0);
    return result;
  }
  Hysteresis c = h;
  // Without the GIL (other Python threads run meanwhile) in chunks of 65536 points;
  // between chunks, with the GIL, a pending Ctrl-C is raised as KeyboardInterrupt.
  constexpr npy_intp kChunk = npy_intp{1} << 16;
  for (npy_intp k0 = 0; k0 < n; k0 += kChunk) {
    const npy_intp k1 = std::min(n, k0 + kChunk);
    {
      nb::gil_scoped_release release;
      for (npy_intp k = k0; k < k1; ++k) {
        double xk = 0.0;
        std::memcpy(&xk, x + k * stride, sizeof xk);
        out[k] = inverse ? c.update_force(xk) : c.update(xk);
      }
    }
    if (PyErr_CheckSignals() != 0) throw nb::python_error();
  }
  return result;
}

MemoryRule parse_rule(const std::string& name) {
  if (name == "masing") return MemoryRule::masing;
  if (name == "reset_at_reversal") return MemoryRule::reset_at_reversal;
  throw InvalidInput(
      "memory rule \"" + name +
      "\" is unknown: allowed are masing (default) and reset_at_reversal (Eq. 7.10)");
}

}  // namespace

void bind_hysteresis(nb::module_& m) {
  nb::class_<Backbone>(m, "Backbone",
                       "A virgin loading curve Q_l(x), x >= 0: odd, non-decreasing, bounded.")
      .def(
          "force",
          [](const Backbone& b, const ArrayLike& x) {
            return vectorize(
                [&b](double v) {
                  core::require_non_negative("displacement x", v);
                  return b.force(v);
                },
                x);
          },
          "x"_a, "Q_l(x) for x >= 0.")
      .def(
          "displacement",
          [](const Backbone& b, const ArrayLike& Q) {
            return vectorize([&b](double v) { return b.displacement(v); }, Q);
          },
          "Q"_a, "Inverse of force for 0 <= Q < limit.")
      .def(
          "integral",
          [](const Backbone& b, const ArrayLike& x) {
            return vectorize([&b](double v) { return b.integral(v); }, x);
          },
          "x"_a, "Int_0^x Q_l.")
      .def_prop_ro("limit", &Backbone::limit, "static friction force, sup Q_l")
      .def_prop_ro("initial_stiffness", &Backbone::initial_stiffness,
                   "dQ_l/dx at 0: the stiffness at every reversal")
      .def(
          "energy_per_cycle",
          [](const Backbone& b, const ArrayLike& x) {
            return vectorize([&b](double v) { return energy_per_cycle(b, v); }, x);
          },
          "x_max"_a, "Energy per symmetric cycle, 8 Int_0^x Q_l - 4 x Q_l(x) (Masing's rules).");

  nb::class_<MindlinBackbone, Backbone>(m, "MindlinBackbone",
                                        "Cattaneo-Mindlin virgin curve of one sphere (B.15).")
      .def(nb::init<const contact::MindlinContact&>(), "contact"_a);
  nb::class_<JenkinsBackbone, Backbone>(m, "JenkinsBackbone",
                                        "Spring k in series with a Coulomb slider F.")
      .def(nb::init<double, double>(), "stiffness"_a, "slip_force"_a);
  nb::class_<ScaledBackbone, Backbone>(m, "ScaledBackbone",
                                       "Q(x) = Q_scale inner(x/x_scale), e.g. a normalized "
                                       "rough-flat backbone in SI units.")
      .def(nb::init<std::shared_ptr<const Backbone>, double, double>(), "inner"_a, "x_scale"_a,
           "Q_scale"_a);

  nb::class_<Hysteresis>(
      m, "Hysteresis",
      "Masing's rules with a reversal stack and loop closing over any backbone: follows any "
      "displacement (or force) history. memory='masing' (default) or 'reset_at_reversal' "
      "(the thesis's Eq. 7.10).")
      .def(
          "__init__",
          [](Hysteresis* self, std::shared_ptr<const Backbone> backbone,
             const std::string& memory) {
            new (self) Hysteresis(std::move(backbone), parse_rule(memory));
          },
          "backbone"_a, "memory"_a = "masing")
      .def("update", &Hysteresis::update, "x"_a,
           "Move to displacement x (reversals detected) and return the force.")
      .def("update_force", &Hysteresis::update_force, "Q"_a,
           "Move to force Q and return the displacement.")
      .def("force", &Hysteresis::force, "x"_a,
           "Force at x by monotone motion from the committed state (no state change).")
      .def("commit_reversal", &Hysteresis::commit_reversal, "x"_a,
           "Commit a reversal of the motion at x (an event).")
      .def("reset", &Hysteresis::reset)
      .def_prop_ro("x", &Hysteresis::x)
      .def_prop_ro("Q", &Hysteresis::Q)
      .def_prop_ro(
          "reversals",
          [](const Hysteresis& h) {
            std::vector<std::pair<double, double>> out;
            for (const auto& r : h.reversals()) out.emplace_back(r.x, r.Q);
            return out;
          },
          "remembered reversal points (x, Q), oldest first")
      .def(
          "forces",
          [](const Hysteresis& h, const ArrayLike& x) { return along_history(h, x, false); }, "x"_a,
          "Forces along a displacement history (1-D array; a float gives a float), from the "
          "current state; the object is not changed.")
      .def(
          "displacements",
          [](const Hysteresis& h, const ArrayLike& Q) { return along_history(h, Q, true); }, "Q"_a,
          "Displacements along a force history (1-D array; a float gives a float), from the "
          "current state; the object is not changed.");
}

}  // namespace asperity::python
