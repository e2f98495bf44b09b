// vibration/: a joint element whose force law is a Python function (issue 23), for every
// harmonic-balance analysis (AFT samples the law in time). The law is memoryless: the
// force at a sample depends on the displacement and velocity at that sample alone.
// python/asperity/vibration.py (UserElement) wraps the user's force and Jacobian (or
// finite differences) into the one callable this element calls.
#include <nanobind/eigen/dense.h>
#include <nanobind/stl/shared_ptr.h>
#include <nanobind/stl/string.h>

#include <fmt/format.h>

#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "asperity/core/error.hpp"
#include "asperity/vibration/elements.hpp"
#include "bindings.hpp"

namespace asperity::python {

using namespace nb::literals;
using namespace asperity::vibration;

namespace {

using Matrix = Eigen::MatrixXd;

// law(u, v, tangent) -> (f, du, dv): f N x D; du, dv N x D^2 in column d + D e
// (d f_d / d u_e, as PeriodicResponse), each may be empty when not needed. The harmonic
// balance releases the GIL while it evaluates, so every call takes it back.
class PythonElement final : public Element {
 public:
  PythonElement(nb::object law, std::size_t directions, bool velocity_dependent, std::string name)
      : law_(nb::weakref(law)),
        directions_(directions),
        velocity_(velocity_dependent),
        name_(std::move(name)) {
    if (directions_ < 1 || directions_ > 64) {
      throw InvalidInput(fmt::format("user element {}: directions = {}: give 1 .. 64 (rows of T)",
                                     name_, directions_));
    }
    // The stuck tangent at rest: the linear modes that start EPMC and the continuations.
    const auto D = static_cast<Eigen::Index>(directions_);
    PeriodicResponse r;
    call(Matrix::Zero(1, D), Matrix::Zero(1, D), true, r);
    K0_.resize(D, D);
    for (Eigen::Index d = 0; d < D; ++d)
      for (Eigen::Index e = 0; e < D; ++e) K0_(d, e) = r.du(0, d + D * e);
  }
  PythonElement(const PythonElement&) = delete;
  PythonElement& operator=(const PythonElement&) = delete;
  ~PythonElement() override {
    if (!Py_IsInitialized()) {
      (void)law_.release();  // the interpreter is gone: nothing left to free
      return;
    }
    nb::gil_scoped_acquire gil;
    law_.reset();
  }

  [[nodiscard]] std::string type() const override { return "user"; }
  [[nodiscard]] std::size_t directions() const override { return directions_; }
  [[nodiscard]] bool velocity_dependent() const override { return velocity_; }
  void periodic_response(const Matrix& u, const Matrix& v, bool tangent,
                         PeriodicResponse& out) const override {
    if (!u.allFinite() || (velocity_ && !v.allFinite())) {
      throw InvalidInput(
          fmt::format("user element {}: a displacement or velocity sample is not "
                      "finite",
                      name_));
    }
    call(u, v, tangent, out);
  }
  void static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f, Matrix& K) const override {
    const auto D = static_cast<Eigen::Index>(directions_);
    if (!u.allFinite()) {
      throw InvalidInput(fmt::format("user element {}: the displacement is not finite", name_));
    }
    PeriodicResponse r;
    call(u.transpose(), Matrix::Zero(1, D), true, r);
    f = r.f.row(0).transpose();
    K.resize(D, D);
    for (Eigen::Index d = 0; d < D; ++d)
      for (Eigen::Index e = 0; e < D; ++e) K(d, e) = r.du(0, d + D * e);
  }
  [[nodiscard]] Matrix initial_stiffness() const override { return K0_; }
  [[nodiscard]] double slip_force() const override {
    return std::numeric_limits<double>::infinity();
  }
  [[nodiscard]] dynamics::SummaryObject describe() const override {
    return {{"type", "user"},
            {"name", name_},
            {"directions", directions_},
            {"velocity_dependent", velocity_}};
  }

 private:
  void call(const Matrix& u, const Matrix& v, bool tangent, PeriodicResponse& out) const {
    const Eigen::Index N = u.rows();
    const auto D = static_cast<Eigen::Index>(directions_);
    nb::gil_scoped_acquire gil;
    const nb::object law = law_();
    if (law.is_none()) {
      throw InvalidInput(fmt::format(
          "user element {}: its Python law was released: keep the UserElement alive", name_));
    }
    const nb::object r =
        law(nb::cast(u, nb::rv_policy::copy), nb::cast(v, nb::rv_policy::copy), tangent);
    if (!nb::isinstance<nb::tuple>(r) || nb::len(r) != 3) {
      throw InvalidInput(
          fmt::format("user element {}: the law must return a tuple (f, du, dv)", name_));
    }
    const auto t = nb::borrow<nb::tuple>(r);
    const auto get = [&](std::size_t k, const char* what, Eigen::Index cols) {
      Matrix m;
      if (!nb::try_cast<Matrix>(t[k], m) || m.rows() != N || m.cols() != cols) {
        throw InvalidInput(fmt::format(
            "user element {}: the law's {} must be a {} x {} array of floats (samples x {})", name_,
            what, N, cols, cols == D ? "directions" : "directions^2"));
      }
      if (!m.allFinite()) {
        throw InvalidInput(
            fmt::format("user element {}: the law's {} holds a NaN or infinity", name_, what));
      }
      return m;
    };
    out.history.clear();
    out.f = get(0, "force f", D);
    if (tangent) {
      out.du = get(1, "Jacobian df/du", D * D);
      if (velocity_) {
        out.dv = get(2, "Jacobian df/dv", D * D);
      } else {
        out.dv.resize(0, 0);
      }
    } else {
      out.du.resize(0, 0);
      out.dv.resize(0, 0);
    }
  }

  nb::weakref law_;
  std::size_t directions_;
  bool velocity_;
  std::string name_;
  Matrix K0_;
};

}  // namespace

void bind_vibration_user(nb::module_& vibration) {
  vibration.def(
      "user_element",
      [](nb::object law, std::size_t directions, bool velocity_dependent, std::string name) {
        if (!PyCallable_Check(law.ptr())) {
          throw InvalidInput(fmt::format("user element {}: the law is not callable", name));
        }
        return std::shared_ptr<const Element>(std::make_shared<PythonElement>(
            std::move(law), directions, velocity_dependent, std::move(name)));
      },
      "law"_a, "directions"_a, "velocity_dependent"_a, "name"_a,
      "A memoryless element from law(u, v, tangent) -> (f, du, dv): u, v and f N x D, du and "
      "dv N x D^2 (column d + D e holds d f_d / d u_e). Holds law weakly: keep it alive; use "
      "asperity.vibration.UserElement.");
}

}  // namespace asperity::python
