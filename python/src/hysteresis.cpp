// hysteresis/: the Masing engine over any backbone (numpy histories in and out).
#include <nanobind/ndarray.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/shared_ptr.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

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

// numpy's C API, imported on first use (this file is its only user); nb::ndarray costs
// 5-6x this path's time on small arrays (docs/performance.md, bench/nb_ndarray).
void import_numpy() {
  static const bool imported = [] {
    if (_import_array() < 0) throw nb::python_error();
    return true;
  }();
  (void)imported;
}

// The `out=` argument of Hysteresis.forces/displacements: None or anything, checked by
// along_history (so that a wrong one is an InvalidInput naming `out`, not a TypeError).
struct OutArray {
  nb::object obj;
};

}  // namespace
}  // namespace asperity::python

namespace nanobind::detail {

template <>
struct type_caster<asperity::python::OutArray> {
  NB_TYPE_CASTER(asperity::python::OutArray, const_name("numpy.typing.NDArray[numpy.float64]"))
  bool from_python(handle src, uint8_t, cleanup_list*) noexcept {
    value.obj = borrow(src);
    return true;
  }
  static handle from_cpp(const asperity::python::OutArray& v, rv_policy, cleanup_list*) noexcept {
    return v.obj.inc_ref();
  }
};

}  // namespace nanobind::detail

namespace asperity::python {
namespace {

// Byte range [first, last) of a 1-D array of doubles (any stride, n > 0).
std::pair<const char*, const char*> byte_range(const char* data, npy_intp n, npy_intp stride) {
  const npy_intp span = (n - 1) * stride;
  return {data + std::min<npy_intp>(0, span),
          data + std::max<npy_intp>(0, span) + static_cast<npy_intp>(sizeof(double))};
}

// The state a history runs on, a copy of `h`: this thread's scratch state, borrowing
// h's backbone (Hysteresis::assign_borrowing: no allocation, no reference count; a
// plain copy allocates its stack, again at the first reversal pushed, and counts a
// reference: 12-20 ns of a 110-170 ns call on 2-8 points, measured), or a plain copy
// when the scratch is in use further up this thread's stack.
class StateCopy {
 public:
  explicit StateCopy(const Hysteresis& h) {
    Scratch& s = scratch();  // one thread-local look-up (a call into the loader)
    if (s.in_use) {
      own_.emplace(h);
      state_ = &*own_;
      return;
    }
    if (!s.state) s.state.emplace(h);
    s.state->assign_borrowing(h);
    s.in_use = true;
    lease_ = &s;
    state_ = &*s.state;
  }
  StateCopy(const StateCopy&) = delete;
  StateCopy& operator=(const StateCopy&) = delete;
  ~StateCopy() {
    if (lease_ != nullptr) lease_->in_use = false;
  }
  Hysteresis& operator*() { return *state_; }

 private:
  struct Scratch {
    std::optional<Hysteresis> state;
    bool in_use = false;
  };
  static Scratch& scratch() {
    thread_local Scratch s;
    return s;
  }
  std::optional<Hysteresis> own_;
  Hysteresis* state_ = nullptr;
  Scratch* lease_ = nullptr;
};

// Below this many points the loop runs with the GIL held: releasing and taking it back
// costs more than the loop (about 10-30 ns a point) and no other thread could use it.
constexpr npy_intp kReleaseGilFrom = 1024;

// Forces (displacements with `inverse`) along a history from the current state of
// `h`, which is not changed. A Python float gives a float; a 1-D float64 numpy array
// (any stride) is read in place and the result written straight into a new array made
// by numpy's C API (a small call costs about a Python call; numpy.empty from Python
// alone costs 4 of them), or into `out` (a writable 1-D float64 array of the same
// length, any stride, returned); anything else goes through numpy.asarray first. An
// `out` overlapping the history other than element for element (the same data and
// stride: in place) makes a copy of the history first.
// `in` and `out_arg` are borrowed (None for no `out`).
nb::object along_history(const Hysteresis& h, nb::handle in, nb::handle out_arg, bool inverse) {
  const char* what = inverse ? "the force history" : "the displacement history";
  const bool has_out = !out_arg.is_none();
  double v = 0.0;
  import_numpy();
  if (!PyArray_CheckExact(in.ptr()) && detail::python_number(in, v)) {
    if (has_out) {
      throw InvalidInput(fmt::format(
          "out is for a 1-D history, but {} is a float ({}), which gives a float: allowed "
          "is out=None here",
          what, core::format_value(v)));
    }
    if (!inverse) return nb::float_(h.peek(v));
    StateCopy c(h);
    return nb::float_((*c).update_force(v));
  }
  nb::handle source = in;
  nb::object converted;  // owns source when it had to be converted
  auto usable = [](PyObject* o) {
    if (!PyArray_Check(o)) return false;
    auto* a = reinterpret_cast<PyArrayObject*>(o);
    return PyArray_NDIM(a) == 1 && PyArray_TYPE(a) == NPY_DOUBLE && PyArray_ISBEHAVED_RO(a);
  };
  if (!usable(source.ptr())) {
    nb::module_ np = nb::module_::import_("numpy");
    converted = np.attr("ascontiguousarray")(np.attr("asarray")(in, nb::arg("dtype") = "float64"));
    source = converted;
    if (!usable(source.ptr())) {
      throw InvalidInput(fmt::format(
          "{} must be a 1-D sequence, got an array with {} dimensions", what,
          PyArray_Check(source.ptr()) ? PyArray_NDIM(reinterpret_cast<PyArrayObject*>(source.ptr()))
                                      : 0));
    }
  }
  auto* a = reinterpret_cast<PyArrayObject*>(source.ptr());
  npy_intp n = PyArray_DIM(a, 0);
  npy_intp stride = PyArray_STRIDE(a, 0);
  const char* x = static_cast<const char*>(PyArray_DATA(a));
  nb::object result;
  char* out = nullptr;
  npy_intp out_stride = sizeof(double);
  if (has_out) {
    PyObject* o = out_arg.ptr();
    auto* oa = PyArray_Check(o) ? reinterpret_cast<PyArrayObject*>(o) : nullptr;
    if (!oa || PyArray_NDIM(oa) != 1 || PyArray_TYPE(oa) != NPY_DOUBLE || !PyArray_ISBEHAVED(oa) ||
        PyArray_DIM(oa, 0) != n) {
      std::string got = fmt::format("a {}", Py_TYPE(o)->tp_name);
      if (oa) {
        std::vector<npy_intp> shape(PyArray_DIMS(oa), PyArray_DIMS(oa) + PyArray_NDIM(oa));
        got =
            fmt::format("a {}{} array of shape ({}{})", PyArray_ISWRITEABLE(oa) ? "" : "read-only ",
                        PyArray_DESCR(oa)->typeobj->tp_name, fmt::join(shape, ", "),
                        shape.size() == 1 ? "," : "");
        if (!PyArray_ISALIGNED(oa) || !PyArray_ISNOTSWAPPED(oa)) {
          got += " (unaligned or byte-swapped)";
        }
      }
      throw InvalidInput(fmt::format(
          "out must be a writable 1-D numpy float64 array (aligned, native byte order, any "
          "stride) of length {}, the length of {}; got {}",
          n, what, got));
    }
    out = static_cast<char*>(PyArray_DATA(oa));
    out_stride = PyArray_STRIDE(oa, 0);
    if (n > 0 && !(out == x && out_stride == stride)) {
      const auto [x_first, x_last] = byte_range(x, n, stride);
      const auto [o_first, o_last] = byte_range(out, n, out_stride);
      if (x_first < o_last && o_first < x_last) {
        // Writing out[k] would overwrite a point not read yet: read from a copy.
        converted = nb::steal(PyArray_NewCopy(a, NPY_CORDER));
        if (!converted.is_valid()) throw nb::python_error();
        source = converted;
        a = reinterpret_cast<PyArrayObject*>(source.ptr());
        stride = PyArray_STRIDE(a, 0);
        x = static_cast<const char*>(PyArray_DATA(a));
      }
    }
    result = nb::borrow(out_arg);
  } else {
    result = nb::steal(PyArray_SimpleNew(1, &n, NPY_DOUBLE));
    if (!result.is_valid()) throw nb::python_error();
    out = static_cast<char*>(PyArray_DATA(reinterpret_cast<PyArrayObject*>(result.ptr())));
  }
  auto point = [&](npy_intp k) {
    double xk = 0.0;
    std::memcpy(&xk, x + k * stride, sizeof xk);
    return xk;
  };
  auto store = [&](npy_intp k, double value) {
    std::memcpy(out + k * out_stride, &value, sizeof value);
  };
  if (n == 1 && !inverse) {
    store(0, h.peek(point(0)));
    return result;
  }
  npy_intp start = 0;
  if (!inverse && n < kReleaseGilFrom && out != x) {
    // The leading points that continue the current branch need no copy of the state;
    // the copy then restarts from the last of them (the same state update() leaves there;
    // not in place, where that point is overwritten by then).
    const auto m = static_cast<npy_intp>(
        h.peek_strided(x, stride, out, out_stride, static_cast<std::size_t>(n)));
    if (m == n) return result;
    start = m > 0 ? m - 1 : 0;
  }
  StateCopy copy(h);
  Hysteresis& c = *copy;
  auto run = [&](npy_intp k0, npy_intp k1) {
    if (inverse) {
      for (npy_intp k = k0; k < k1; ++k) store(k, c.update_force(point(k)));
    } else {
      c.update_strided(x + k0 * stride, stride, out + k0 * out_stride, out_stride,
                       static_cast<std::size_t>(k1 - k0));
    }
  };
  if (n < kReleaseGilFrom) {
    run(start, n);
    return result;
  }
  // Without the GIL (other Python threads run meanwhile) in chunks of 65536 points;
  // between chunks, with the GIL, a pending Ctrl-C is raised as KeyboardInterrupt.
  constexpr npy_intp kChunk = npy_intp{1} << 16;
  for (npy_intp k0 = 0; k0 < n; k0 += kChunk) {
    const npy_intp k1 = std::min(n, k0 + kChunk);
    {
      nb::gil_scoped_release release;
      run(k0, k1);
    }
    if (PyErr_CheckSignals() != 0) throw nb::python_error();
  }
  return result;
}

// Hysteresis.forces / Hysteresis.displacements as CPython method descriptors
// (METH_FASTCALL | METH_KEYWORDS): the interpreter calls them without nanobind's argument
// dispatch, which is most of a small call's cost, and inspect.signature reads their
// __text_signature__ (the first docstring line). The same along_history as the nanobind
// methods, which the stub generator sees (asperity/__init__.py installs these).
template <bool Inverse>
PyObject* history_method(PyObject* self, PyObject* const* args, Py_ssize_t nargs,
                         PyObject* kwnames) {
  const char* name = Inverse ? "displacements" : "forces";
  const char* first = Inverse ? "Q" : "x";
  PyObject* history = nargs >= 1 ? args[0] : nullptr;
  PyObject* out = Py_None;
  if (nargs > 1) {
    PyErr_Format(PyExc_TypeError, "%s() takes 1 positional argument (%s) but %zd were given", name,
                 first, nargs);
    return nullptr;
  }
  if (kwnames != nullptr) {
    // Keyword names in a call are interned by the compiler: compared by identity first
    // (a string comparison cost about a tenth of a small call, measured).
    static PyObject* const out_name = PyUnicode_InternFromString("out");
    static PyObject* const first_name = PyUnicode_InternFromString(first);
    for (Py_ssize_t i = 0; i < PyTuple_GET_SIZE(kwnames); ++i) {
      PyObject* key = PyTuple_GET_ITEM(kwnames, i);
      const bool is_out = key == out_name ||
                          (key != first_name && PyUnicode_CompareWithASCIIString(key, "out") == 0);
      if (is_out) {
        out = args[nargs + i];
      } else if ((key == first_name || PyUnicode_CompareWithASCIIString(key, first) == 0) &&
                 history == nullptr) {
        history = args[nargs + i];
      } else {
        PyErr_Format(PyExc_TypeError, "%s() got an unexpected or repeated keyword argument '%U'",
                     name, key);
        return nullptr;
      }
    }
  }
  if (history == nullptr) {
    PyErr_Format(PyExc_TypeError, "%s() missing required argument '%s'", name, first);
    return nullptr;
  }
  if (history == Py_None) {  // as the nanobind method (its argument caster refuses None)
    PyErr_Format(PyExc_TypeError, "%s(): %s must be a float or a 1-D array of floats, not None",
                 name, first);
    return nullptr;
  }
  if (!nb::inst_ready(self)) {
    PyErr_Format(PyExc_TypeError, "%s(): the Hysteresis object is not initialized", name);
    return nullptr;
  }
  try {
    return along_history(*nb::inst_ptr<Hysteresis>(self), history, out, Inverse).release().ptr();
  } catch (...) {
    set_python_error_from_current_exception();
    return nullptr;
  }
}

constexpr const char* kForcesDoc =
    "forces($self, /, x, *, out=None)\n--\n\n"
    "Forces along a displacement history (1-D array; a float gives a float), from the current "
    "state; the object is not changed. out: a writable 1-D float64 array of the history's "
    "length (any stride; it may be x itself) to write the forces into and return, instead of "
    "a new array.";
constexpr const char* kDisplacementsDoc =
    "displacements($self, /, Q, *, out=None)\n--\n\n"
    "Displacements along a force history (1-D array; a float gives a float), from the current "
    "state; the object is not changed. out: a writable 1-D float64 array of the history's "
    "length (any stride; it may be Q itself) to write the displacements into and return, "
    "instead of a new array.";

PyMethodDef g_history_methods[] = {
    {"forces", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&history_method<false>)),
     METH_FASTCALL | METH_KEYWORDS, kForcesDoc},
    {"displacements",
     reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&history_method<true>)),
     METH_FASTCALL | METH_KEYWORDS, kDisplacementsDoc}};

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

  auto hysteresis =
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
              [](const Hysteresis& h, const ArrayLike& x, const OutArray& out) {
                return FloatOrArray{along_history(h, x.obj, out.obj, false)};
              },
              "x"_a, nb::kw_only(), "out"_a = nb::none(),
              "Forces along a displacement history (1-D array; a float gives a float), from the "
              "current state; the object is not changed. out: a writable 1-D float64 array of the "
              "history's length (any stride; it may be x itself) to write the forces into and "
              "return, instead of a new array.")
          .def(
              "displacements",
              [](const Hysteresis& h, const ArrayLike& Q, const OutArray& out) {
                return FloatOrArray{along_history(h, Q.obj, out.obj, true)};
              },
              "Q"_a, nb::kw_only(), "out"_a = nb::none(),
              "Displacements along a force history (1-D array; a float gives a float), from the "
              "current state; the object is not changed. out: a writable 1-D float64 array of the "
              "history's length (any stride; it may be Q itself) to write the displacements into "
              "and return, instead of a new array.");
  m.def(
      "_install_fast_history_methods",
      [hysteresis]() {
        auto* type = reinterpret_cast<PyTypeObject*>(hysteresis.ptr());
        for (PyMethodDef& def : g_history_methods) {
          nb::object descriptor = nb::steal(PyDescr_NewMethod(type, &def));
          if (!descriptor.is_valid()) throw nb::python_error();
          hysteresis.attr(def.ml_name) = descriptor;
        }
      },
      "Replaces Hysteresis.forces and .displacements by CPython method descriptors (same "
      "behaviour, faster small calls); asperity/__init__.py calls it.");
}

}  // namespace asperity::python
