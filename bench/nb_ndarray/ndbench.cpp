// The array in/out of Hysteresis.forces(x) two ways, same raw METH_FASTCALL entry and
// the same per-point work: numpy's C API (as python/src/hysteresis.cpp) vs nb::ndarray.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#include <numpy/arrayobject.h>
#include <cmath>
namespace nb = nanobind;

static double f(double x) {
  return std::tanh(x);
}

static PyObject* capi(PyObject*, PyObject* const* args, Py_ssize_t nargs) {
  if (nargs != 1 || !PyArray_Check(args[0])) {
    PyErr_SetString(PyExc_TypeError, "array");
    return nullptr;
  }
  auto* a = reinterpret_cast<PyArrayObject*>(args[0]);
  if (PyArray_NDIM(a) != 1 || PyArray_TYPE(a) != NPY_DOUBLE || !PyArray_ISBEHAVED_RO(a)) {
    PyErr_SetString(PyExc_TypeError, "f8");
    return nullptr;
  }
  npy_intp n = PyArray_DIM(a, 0);
  npy_intp st = PyArray_STRIDE(a, 0);
  const char* x = static_cast<const char*>(PyArray_DATA(a));
  PyObject* r = PyArray_SimpleNew(1, &n, NPY_DOUBLE);
  if (!r) return nullptr;
  double* o = static_cast<double*>(PyArray_DATA(reinterpret_cast<PyArrayObject*>(r)));
  for (npy_intp i = 0; i < n; ++i) o[i] = f(*reinterpret_cast<const double*>(x + i * st));
  return r;
}

using In = nb::ndarray<const double, nb::ndim<1>, nb::device::cpu>;
using Out = nb::ndarray<nb::numpy, double, nb::ndim<1>>;

static PyObject* ndarr(PyObject*, PyObject* const* args, Py_ssize_t nargs) {
  try {
    nb::detail::make_caster<In> c;
    nb::detail::cleanup_list cl(nullptr);
    if (nargs != 1 || !c.from_python(args[0], 0, &cl)) {
      cl.release();
      PyErr_SetString(PyExc_TypeError, "array");
      return nullptr;
    }
    cl.release();
    const In& a = c.value;
    const size_t n = a.shape(0);
    double* o = new double[n];
    nb::capsule owner(o, [](void* p) noexcept { delete[] static_cast<double*>(p); });
    auto v = a.view();
    for (size_t i = 0; i < n; ++i) o[i] = f(v(i));
    return Out(o, {n}, owner).cast().release().ptr();
  } catch (nb::python_error& e) {
    e.restore();
    return nullptr;
  } catch (std::exception& e) {
    PyErr_SetString(PyExc_RuntimeError, e.what());
    return nullptr;
  }
}

// Import only (sum to a float) and export only (a new n-array from a float), each way.
static double capi_in_impl(PyObject* o) {
  auto* a = reinterpret_cast<PyArrayObject*>(o);
  const char* x = static_cast<const char*>(PyArray_DATA(a));
  double s = 0;
  for (npy_intp i = 0; i < PyArray_DIM(a, 0); ++i)
    s += *reinterpret_cast<const double*>(x + i * PyArray_STRIDE(a, 0));
  return s;
}
static PyObject* capi_in(PyObject*, PyObject* const* args, Py_ssize_t) {
  if (!PyArray_Check(args[0])) return nullptr;
  return PyFloat_FromDouble(capi_in_impl(args[0]));
}
static PyObject* ndarr_in(PyObject*, PyObject* const* args, Py_ssize_t) {
  nb::detail::make_caster<In> c;
  nb::detail::cleanup_list cl(nullptr);
  if (!c.from_python(args[0], 0, &cl)) {
    cl.release();
    PyErr_SetString(PyExc_TypeError, "array");
    return nullptr;
  }
  cl.release();
  auto v = c.value.view();
  double s = 0;
  for (size_t i = 0; i < c.value.shape(0); ++i) s += v(i);
  return PyFloat_FromDouble(s);
}
static PyObject* capi_out(PyObject*, PyObject* const* args, Py_ssize_t) {
  npy_intp n = 1;
  double x = PyFloat_AsDouble(args[0]);
  PyObject* r = PyArray_SimpleNew(1, &n, NPY_DOUBLE);
  static_cast<double*>(PyArray_DATA(reinterpret_cast<PyArrayObject*>(r)))[0] = x;
  return r;
}
static PyObject* ndarr_out(PyObject*, PyObject* const* args, Py_ssize_t) {
  double* o = new double[1];
  o[0] = PyFloat_AsDouble(args[0]);
  nb::capsule owner(o, [](void* p) noexcept { delete[] static_cast<double*>(p); });
  return Out(o, {1}, owner).cast().release().ptr();
}

// Same but through ordinary nanobind dispatch (the natural nb::ndarray code).
static Out ndarr_dispatch(In a) {
  const size_t n = a.shape(0);
  double* o = new double[n];
  nb::capsule owner(o, [](void* p) noexcept { delete[] static_cast<double*>(p); });
  auto v = a.view();
  for (size_t i = 0; i < n; ++i) o[i] = f(v(i));
  return Out(o, {n}, owner);
}

static PyMethodDef defs[] = {
    {"capi", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(capi)), METH_FASTCALL,
     nullptr},
    {"ndarr", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(ndarr)), METH_FASTCALL,
     nullptr},
    {"capi_in", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(capi_in)), METH_FASTCALL,
     nullptr},
    {"ndarr_in", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(ndarr_in)),
     METH_FASTCALL, nullptr},
    {"capi_out", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(capi_out)),
     METH_FASTCALL, nullptr},
    {"ndarr_out", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(ndarr_out)),
     METH_FASTCALL, nullptr},
    {nullptr, nullptr, 0, nullptr}};

NB_MODULE(ndbench, m) {
  if (_import_array() < 0) throw nb::python_error();
  for (PyMethodDef* d = defs; d->ml_name; ++d)
    m.attr(d->ml_name) = nb::steal(PyCFunction_NewEx(d, nullptr, m.ptr()));
  m.def("ndarr_dispatch", &ndarr_dispatch);
}
