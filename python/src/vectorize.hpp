#pragma once
// Vectorization of scalar C++ functions over numpy arrays, shared by the bindings of
// every layer. Python scalars in give a float out; anything numpy can turn into a
// float64 array gives an array of the broadcast shape out. The loop runs in C++; the
// function itself holds the physics, this file none.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include "asperity/core/parallel.hpp"

namespace asperity::python {

namespace nb = nanobind;

/// A float or anything array-like (list, tuple, numpy array of any shape).
struct ArrayLike {
  nb::object obj;
};

/// What a vectorized function returns: a float, or a numpy float64 array.
struct FloatOrArray {
  nb::object obj;
};

}  // namespace asperity::python

namespace nanobind::detail {

template <>
struct type_caster<asperity::python::ArrayLike> {
  NB_TYPE_CASTER(asperity::python::ArrayLike, const_name("float | numpy.typing.ArrayLike"))
  bool from_python(handle src, uint8_t, cleanup_list*) noexcept {
    if (src.is_none()) return false;
    value.obj = borrow(src);
    return true;
  }
  static handle from_cpp(const asperity::python::ArrayLike& v, rv_policy, cleanup_list*) noexcept {
    return v.obj.inc_ref();
  }
};

template <>
struct type_caster<asperity::python::FloatOrArray> {
  NB_TYPE_CASTER(asperity::python::FloatOrArray,
                 const_name("float | numpy.typing.NDArray[numpy.float64]"))
  bool from_python(handle, uint8_t, cleanup_list*) noexcept { return false; }
  static handle from_cpp(const asperity::python::FloatOrArray& v, rv_policy,
                         cleanup_list*) noexcept {
    return v.obj.inc_ref();
  }
};

}  // namespace nanobind::detail

namespace asperity::python {

namespace detail {

using ConstView = nb::ndarray<const double, nb::c_contig, nb::device::cpu>;

/// True (and the value) for a Python float or int, the fast path.
inline bool python_number(nb::handle h, double& out) {
  if (!PyFloat_Check(h.ptr()) && !PyLong_Check(h.ptr())) return false;
  out = PyFloat_AsDouble(h.ptr());
  if (out == -1.0 && PyErr_Occurred()) throw nb::python_error();
  return true;
}

/// A new numpy float64 array of the given shape owning `data`.
inline nb::object make_array(std::unique_ptr<double[]> data, const std::vector<size_t>& shape) {
  double* raw = data.get();
  nb::capsule owner(raw, [](void* p) noexcept { delete[] static_cast<double*>(p); });
  (void)data.release();
  return nb::ndarray<nb::numpy, double>(raw, shape.size(), shape.data(), owner).cast();
}

template <class F, std::size_t... I>
FloatOrArray vectorize_impl(F& f, const std::array<nb::handle, sizeof...(I)>& in,
                            std::index_sequence<I...>) {
  constexpr std::size_t N = sizeof...(I);
  std::array<double, N> scalars{};
  bool all_numbers = true;
  for (std::size_t i = 0; i < N; ++i) all_numbers = all_numbers && python_number(in[i], scalars[i]);
  if (all_numbers) return {nb::float_(f(scalars[I]...))};

  nb::module_ np = nb::module_::import_("numpy");
  nb::list arrays;
  for (std::size_t i = 0; i < N; ++i) {
    arrays.append(np.attr("asarray")(in[i], nb::arg("dtype") = "float64"));
  }
  nb::object broadcast = N == 1 ? nb::object(arrays) : np.attr("broadcast_arrays")(*arrays);
  std::array<nb::object, N> owners;
  std::array<ConstView, N> views;
  for (std::size_t i = 0; i < N; ++i) {
    // asarray keeps 0-d arrays 0-d (ascontiguousarray would make them 1-d).
    owners[i] =
        np.attr("asarray")(broadcast[i], nb::arg("dtype") = "float64", nb::arg("order") = "C");
    views[i] = nb::cast<ConstView>(owners[i]);
  }
  const std::size_t ndim = views[0].ndim();
  if (ndim == 0) return {nb::float_(f(views[I].data()[0]...))};
  std::vector<size_t> shape(ndim);
  for (std::size_t d = 0; d < ndim; ++d) shape[d] = views[0].shape(d);
  const std::size_t n = views[0].size();
  auto out = std::make_unique<double[]>(n);
  // Large arrays in blocks over the cores (core::parallel_for: every element in its own
  // slot, so the result is the sequential one; the first error by index is raised), without
  // the GIL (other Python threads run meanwhile), 4 blocks per thread between checks for a
  // pending Ctrl-C (raised as KeyboardInterrupt). Small ones stay on this thread with the
  // GIL: a small call costs about a Python call.
  constexpr std::size_t kBlock = 8192;
  const std::array<const double*, N> data{views[I].data()...};
  double* o = out.get();
  auto block = [&](std::size_t b) {
    const std::size_t end = std::min(n, (b + 1) * kBlock);
    for (std::size_t k = b * kBlock; k < end; ++k) o[k] = f(data[I][k]...);
  };
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  if (blocks <= 1) {
    block(0);
  } else {
    const std::size_t per_check = 4 * std::max<std::size_t>(1, core::worker_count());
    for (std::size_t b0 = 0; b0 < blocks; b0 += per_check) {
      const std::size_t nb = std::min(per_check, blocks - b0);
      {
        nb::gil_scoped_release release;
        core::parallel_for(nb, [&](std::size_t b) { block(b0 + b); });
      }
      if (PyErr_CheckSignals() != 0) throw nb::python_error();
    }
  }
  return {make_array(std::move(out), shape)};
}

}  // namespace detail

/// Applies `f(double, ...) -> double` elementwise over broadcast numpy arrays. All
/// arguments Python numbers (or 0-d arrays) -> float; otherwise an array of the
/// broadcast shape. Errors thrown by `f` propagate (the first one wins). Above 8192
/// elements the loop runs on worker threads without the GIL and checks for signals every
/// 4 blocks of 8192 per thread, so `f` must not touch Python objects.
template <class F, class... A>
FloatOrArray vectorize(F&& f, const A&... args) {
  const std::array<nb::handle, sizeof...(A)> in{nb::handle(args.obj)...};
  return detail::vectorize_impl(f, in, std::index_sequence_for<A...>{});
}

/// A read-only 1-D numpy view of a std::vector owned by the Python object `owner`
/// (pass nb::handle() together with rv_policy::reference_internal on properties).
template <class T>
nb::ndarray<nb::numpy, const T, nb::ndim<1>> view_of(const std::vector<T>& v,
                                                     nb::handle owner = nb::handle()) {
  return nb::ndarray<nb::numpy, const T, nb::ndim<1>>(v.data(), {v.size()}, owner);
}

/// A new 1-D numpy array holding a copy of `v`.
inline nb::object array_of(const std::vector<double>& v) {
  auto data = std::make_unique<double[]>(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) data[i] = v[i];
  return detail::make_array(std::move(data), {v.size()});
}

}  // namespace asperity::python
