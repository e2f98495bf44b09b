// Callables that carry an inspect.Signature: nanobind's functions and methods keep their
// signatures as text only (__nb_signature__), and their types accept no new attributes,
// so inspect.signature() fails on them. asperity/_signatures.py parses that text and
// wraps each public function and method in one of the two types below: a C-level
// forwarder with an instance __dict__ (for __signature__, __doc__, __name__, ...), whose
// call passes the arguments on unchanged through the vectorcall protocol. A method
// wrapper is a method descriptor like nanobind's own (Py_TPFLAGS_METHOD_DESCRIPTOR:
// `obj.method(x)` calls it with obj prepended, no bound object made); a function wrapper
// (module functions, static methods) never binds.
#include <cstddef>

#include "bindings.hpp"  // nanobind, hence Python.h, first

#include <structmember.h>

namespace asperity::python {

namespace {

PyTypeObject* g_function_type = nullptr;
PyTypeObject* g_method_type = nullptr;

struct SignedCallable {
  PyObject_HEAD PyObject* target;  // the nanobind function or method
  PyObject* dict;                  // __signature__, __doc__, __name__, __qualname__, ...
  vectorcallfunc vectorcall;
  vectorcallfunc target_vectorcall;  // the target's own entry point (nanobind's are vectorcall)
};

PyObject* signed_vectorcall(PyObject* self, PyObject* const* args, std::size_t nargsf,
                            PyObject* kwnames) {
  auto* s = reinterpret_cast<SignedCallable*>(self);
  if (s->target == nullptr) {  // cleared by the garbage collector (a finalizer's call)
    PyErr_SetString(PyExc_ReferenceError, "the compiled callable was cleared");
    return nullptr;
  }
  return s->target_vectorcall != nullptr ? s->target_vectorcall(s->target, args, nargsf, kwnames)
                                         : PyObject_Vectorcall(s->target, args, nargsf, kwnames);
}

int signed_traverse(PyObject* self, visitproc visit, void* arg) {
  auto* s = reinterpret_cast<SignedCallable*>(self);
  Py_VISIT(s->target);
  Py_VISIT(s->dict);
  Py_VISIT(Py_TYPE(self));  // heap type
  return 0;
}

int signed_clear(PyObject* self) {
  auto* s = reinterpret_cast<SignedCallable*>(self);
  Py_CLEAR(s->target);
  Py_CLEAR(s->dict);
  return 0;
}

void signed_dealloc(PyObject* self) {
  PyTypeObject* type = Py_TYPE(self);
  PyObject_GC_UnTrack(self);
  signed_clear(self);
  type->tp_free(self);
  Py_DECREF(type);
}

PyObject* signed_repr(PyObject* self) {
  auto* s = reinterpret_cast<SignedCallable*>(self);
  PyObject* name = s->dict != nullptr ? PyDict_GetItemString(s->dict, "__qualname__") : nullptr;
  if (name == nullptr || !PyUnicode_Check(name)) {
    return s->target != nullptr ? PyObject_Repr(s->target) : PyUnicode_FromString("<cleared>");
  }
  return PyUnicode_FromFormat("<compiled %s %U>",
                              Py_TYPE(self) == g_method_type ? "method" : "function", name);
}

// Pickled and copied by reference, as Python's own functions are: the qualified name,
// found again as __module__.__qualname__ (asperity.bolt_preload, asperity.Hysteresis.update).
PyObject* signed_reduce(PyObject* self, PyObject*) {
  auto* s = reinterpret_cast<SignedCallable*>(self);
  PyObject* name = s->dict != nullptr ? PyDict_GetItemString(s->dict, "__qualname__") : nullptr;
  if (name == nullptr || !PyUnicode_Check(name)) {
    PyErr_SetString(PyExc_TypeError, "cannot pickle a compiled callable without __qualname__");
    return nullptr;
  }
  return Py_NewRef(name);
}

PyMethodDef signed_methods[] = {
    {"__reduce__", signed_reduce, METH_NOARGS, "pickled by reference (its qualified name)"},
    {nullptr, nullptr, 0, nullptr}};

PyGetSetDef signed_getset[] = {
    {"__dict__", PyObject_GenericGetDict, PyObject_GenericSetDict, nullptr, nullptr},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

// Looked up on the class (obj == NULL or None): the wrapper itself, so that
// inspect.signature(Class.method) finds its __signature__; on an instance: a bound method.
PyObject* signed_method_get(PyObject* self, PyObject* obj, PyObject*) {
  if (obj == nullptr || obj == Py_None) return Py_NewRef(self);
  return PyMethod_New(self, obj);
}

PyMemberDef signed_members[] = {
    {"__dictoffset__", T_PYSSIZET, offsetof(SignedCallable, dict), READONLY, nullptr},
    {"__vectorcalloffset__", T_PYSSIZET, offsetof(SignedCallable, vectorcall), READONLY, nullptr},
    {"__wrapped__", T_OBJECT, offsetof(SignedCallable, target), READONLY,
     "the nanobind function or method called"},
    {nullptr, 0, 0, 0, nullptr}};

// The slots of both forwarder types; a method's type also binds to an instance like a
// method descriptor (tp_descr_get). The function type's list ends one entry early.
template <bool Method>
PyType_Slot* forwarder_slots() {
  static PyType_Slot slots[] = {
      {Py_tp_dealloc, reinterpret_cast<void*>(signed_dealloc)},
      {Py_tp_traverse, reinterpret_cast<void*>(signed_traverse)},
      {Py_tp_clear, reinterpret_cast<void*>(signed_clear)},
      {Py_tp_call, reinterpret_cast<void*>(PyVectorcall_Call)},
      {Py_tp_repr, reinterpret_cast<void*>(signed_repr)},
      {Py_tp_methods, signed_methods},
      {Py_tp_getset, signed_getset},
      {Py_tp_members, signed_members},
      Method ? PyType_Slot{Py_tp_descr_get, reinterpret_cast<void*>(signed_method_get)}
             : PyType_Slot{0, nullptr},
      {0, nullptr}};
  return slots;
}

constexpr unsigned long kFlags = Py_TPFLAGS_DEFAULT | Py_TPFLAGS_HAVE_GC |
                                 Py_TPFLAGS_HAVE_VECTORCALL | Py_TPFLAGS_DISALLOW_INSTANTIATION |
                                 Py_TPFLAGS_IMMUTABLETYPE;

PyType_Spec function_spec = {"asperity._core.signed_function",
                             static_cast<int>(sizeof(SignedCallable)), 0, kFlags,
                             forwarder_slots<false>()};
PyType_Spec method_spec = {"asperity._core.signed_method", static_cast<int>(sizeof(SignedCallable)),
                           0, kFlags | Py_TPFLAGS_METHOD_DESCRIPTOR, forwarder_slots<true>()};

nb::object make_signed(nb::handle target, bool method) {
  PyTypeObject* type = method ? g_method_type : g_function_type;
  PyObject* o = type->tp_alloc(type, 0);
  if (o == nullptr) throw nb::python_error();
  auto* s = reinterpret_cast<SignedCallable*>(o);
  s->target = Py_NewRef(target.ptr());
  s->dict = PyDict_New();
  s->vectorcall = signed_vectorcall;
  s->target_vectorcall = PyVectorcall_Function(target.ptr());
  if (s->dict == nullptr) {
    Py_DECREF(o);
    throw nb::python_error();
  }
  return nb::steal(o);
}

}  // namespace

void bind_signatures(nb::module_& m) {
  g_function_type = reinterpret_cast<PyTypeObject*>(PyType_FromSpec(&function_spec));
  if (g_function_type == nullptr) throw nb::python_error();
  g_method_type = reinterpret_cast<PyTypeObject*>(PyType_FromSpec(&method_spec));
  if (g_method_type == nullptr) throw nb::python_error();
  // Both types live as long as the interpreter (the references above are never released).
  m.def("_signed", &make_signed, nb::arg("target"), nb::arg("method"),
        "A forwarder to `target` with an instance __dict__ (asperity/_signatures.py sets "
        "__signature__ and the names there); `method` makes it bind like a method.");
}

}  // namespace asperity::python
