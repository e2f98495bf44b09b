// core/: the exception hierarchy and quantities with units.
#include <fmt/format.h>
#include <nanobind/stl/string.h>

#include <asperity/core/error.hpp>
#include <asperity/core/parallel.hpp>
#include <asperity/core/units.hpp>
#include <asperity/core/version.hpp>
#include <new>
#include <stdexcept>
#include <string>

#include "bindings.hpp"

namespace asperity::python {

namespace {

PyObject* g_error = nullptr;
PyObject* g_invalid_input = nullptr;
PyObject* g_numerical_error = nullptr;

PyObject* new_exception(const char* name, const char* doc, PyObject* bases) {
  PyObject* type = PyErr_NewExceptionWithDoc(name, doc, bases, nullptr);
  if (type == nullptr) throw nb::python_error();
  return type;
}

}  // namespace

void set_python_error_from_current_exception() {
  // The library's errors as the translator registered in bind_core sets them; the
  // standard exceptions as nanobind's built-in translation does.
  try {
    throw;
  } catch (nb::python_error& e) {
    e.restore();
  } catch (const InvalidInput& e) {
    PyErr_SetString(g_invalid_input, e.what());
  } catch (const NumericalError& e) {
    PyErr_SetString(g_numerical_error, e.what());
  } catch (const Error& e) {
    PyErr_SetString(g_error, e.what());
  } catch (const std::bad_alloc&) {
    PyErr_NoMemory();
  } catch (const std::out_of_range& e) {
    PyErr_SetString(PyExc_IndexError, e.what());
  } catch (const std::overflow_error& e) {
    PyErr_SetString(PyExc_OverflowError, e.what());
  } catch (const std::invalid_argument& e) {
    PyErr_SetString(PyExc_ValueError, e.what());
  } catch (const std::domain_error& e) {
    PyErr_SetString(PyExc_ValueError, e.what());
  } catch (const std::length_error& e) {
    PyErr_SetString(PyExc_ValueError, e.what());
  } catch (const std::range_error& e) {
    PyErr_SetString(PyExc_ValueError, e.what());
  } catch (const std::exception& e) {
    PyErr_SetString(PyExc_RuntimeError, e.what());
  } catch (...) {
    PyErr_SetString(PyExc_SystemError, "an unknown C++ exception");
  }
}

void bind_core(nb::module_& m) {
  m.def(
      "version_info",
      [] {
        const auto v = core::version_info();
        nb::dict d;
        d["version"] = std::string(v.version);
        d["git_revision"] = std::string(v.git_revision);
        d["build_type"] = std::string(v.build_type);
        return d;
      },
      "The version of the compiled library: {'version', 'git_revision', 'build_type'} (as "
      "`asperity --version` prints them).");
  m.def(
      "thread_count", [] { return core::worker_count(); },
      "Threads the library's parallel loops use (load cases of predict, rows and columns of "
      "areal roughness, large vectorized calls): ASPERITY_THREADS, else the number of cores, "
      "unless set_thread_count() changed it.");
  m.def(
      "set_thread_count",
      [](long long n) {
        if (n < 1) {
          throw InvalidInput(fmt::format("thread count {} is not allowed: 1 to 256", n));
        }
        core::set_worker_count(static_cast<std::size_t>(n));
      },
      nb::arg("n"),
      "Sets the threads of the library's parallel loops for this process (1 to 256). Results "
      "do not depend on it. asperity.sweep sets 1 in its workers: the samples are the "
      "parallel dimension there.");
  // asperity.Error is the base of both; InvalidInput is also a ValueError and
  // NumericalError a RuntimeError, so generic `except ValueError` code works.
  g_error =
      new_exception("asperity.Error", "Base of every error raised by asperity.", PyExc_Exception);
  nb::object invalid_bases = nb::make_tuple(nb::handle(g_error), nb::handle(PyExc_ValueError));
  g_invalid_input = new_exception(
      "asperity.InvalidInput",
      "Bad user data (C++ asperity::InvalidInput). The message names the field, its value "
      "and what is allowed.",
      invalid_bases.ptr());
  nb::object numerical_bases = nb::make_tuple(nb::handle(g_error), nb::handle(PyExc_RuntimeError));
  g_numerical_error = new_exception(
      "asperity.NumericalError",
      "A solve or an integral that failed (C++ asperity::NumericalError); the message says "
      "what was tried.",
      numerical_bases.ptr());
  // The module keeps the references for the lifetime of the interpreter.
  m.attr("Error") = nb::handle(g_error);
  m.attr("InvalidInput") = nb::handle(g_invalid_input);
  m.attr("NumericalError") = nb::handle(g_numerical_error);

  nb::register_exception_translator([](const std::exception_ptr& p, void*) {
    try {
      std::rethrow_exception(p);
    } catch (const Error&) {
      set_python_error_from_current_exception();  // one mapping for both entry points
    }
  });

  using core::Dimension;
  using core::Quantity;
  nb::class_<Dimension>(m, "Dimension", "Exponents of metre, kilogram and second of a quantity.")
      .def(nb::init<>())
      .def_rw("m", &Dimension::m)
      .def_rw("kg", &Dimension::kg)
      .def_rw("s", &Dimension::s)
      .def("__eq__", [](const Dimension& a, const Dimension& b) { return a == b; })
      .def("__repr__",
           [](const Dimension& d) {
             return fmt::format("Dimension(m={}, kg={}, s={})", d.m, d.kg, d.s);
           })
      .def("__str__", [](const Dimension& d) { return core::dimension_name(d); });
  nb::class_<Quantity>(m, "Quantity", "A value in SI base units and its dimension.")
      .def_ro("value", &Quantity::value)
      .def_ro("dimension", &Quantity::dimension)
      .def("__float__", [](const Quantity& q) { return q.value; })
      .def("__repr__", [](const Quantity& q) {
        return fmt::format("Quantity(value={}, dimension='{}')", q.value,
                           core::dimension_name(q.dimension));
      });
  m.def("dimension_name", &core::dimension_name, nb::arg("dimension"),
        "Readable name of a dimension ('length', 'pressure', or 'm^2 kg s^-2').");
  m.def(
      "parse_quantity",
      [](const std::string& text, const std::string& field) {
        return core::parse_quantity(text, field);
      },
      nb::arg("text"), nb::arg("field") = "quantity",
      "Parses '<number> [unit]' (e.g. '207 GPa', '2.91e-4 um^-2', '1.7 lbf*in') into SI. "
      "Raises InvalidInput naming `field` on malformed text or an unknown unit.");
}

}  // namespace asperity::python
