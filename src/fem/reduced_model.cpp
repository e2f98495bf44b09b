#include "asperity/fem/reduced_model.hpp"

// Eigen's dense eigensolvers, inlined at -O3, make g++ 12 see potential null dereferences
// (a known false positive of -Wnull-dereference).
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include <matio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"

namespace asperity::fem {
namespace {

struct MatCloser {
  void operator()(mat_t* m) const { Mat_Close(m); }
};
struct VarFreer {
  void operator()(matvar_t* v) const { Mat_VarFree(v); }
};
using MatFile = std::unique_ptr<mat_t, MatCloser>;
using MatVar = std::unique_ptr<matvar_t, VarFreer>;

void write_matrix(mat_t* mat, const char* name, const Eigen::MatrixXd& m, const std::string& path) {
  std::size_t dims[2] = {static_cast<std::size_t>(m.rows()), static_cast<std::size_t>(m.cols())};
  Eigen::MatrixXd copy = m;  // column-major, as MATLAB stores it
  MatVar var(Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, copy.data(), 0));
  if (!var || Mat_VarWrite(mat, var.get(), MAT_COMPRESSION_NONE) != 0)
    throw InvalidInput(fmt::format("cannot write matrix {} to \"{}\"", name, path));
}

void write_text(mat_t* mat, const char* name, const std::string& text, const std::string& path) {
  std::string copy = text.empty() ? std::string(" ") : text;
  std::size_t dims[2] = {1, copy.size()};
  MatVar var(Mat_VarCreate(name, MAT_C_CHAR, MAT_T_UINT8, 2, dims, copy.data(), 0));
  if (!var || Mat_VarWrite(mat, var.get(), MAT_COMPRESSION_NONE) != 0)
    throw InvalidInput(fmt::format("cannot write {} to \"{}\"", name, path));
}

std::string join_lines(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? "\n" : "") + names[i];
  return s;
}

std::vector<std::string> split_lines(const std::string& s, std::size_t count) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  out.resize(count);
  return out;
}

// A real matrix (full or sparse, any numeric class) as dense doubles; nullopt if absent.
std::optional<Eigen::MatrixXd> read_matrix(mat_t* mat, const char* name, const std::string& path) {
  MatVar var(Mat_VarRead(mat, name));
  if (!var) return std::nullopt;
  if (var->rank != 2 || var->isComplex)
    throw InvalidInput(fmt::format("\"{}\": matrix {} is not a real 2-D matrix", path, name));
  const auto rows = static_cast<Eigen::Index>(var->dims[0]),
             cols = static_cast<Eigen::Index>(var->dims[1]);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(rows, cols);
  if (var->class_type == MAT_C_SPARSE) {
    const auto* sp = static_cast<const mat_sparse_t*>(var->data);
    if (var->data_type != MAT_T_DOUBLE)
      throw InvalidInput(fmt::format("\"{}\": sparse matrix {} is not double", path, name));
    const auto* values = static_cast<const double*>(sp->data);
    for (Eigen::Index c = 0; c < cols && c + 1 < static_cast<Eigen::Index>(sp->njc); ++c)
      for (auto k = sp->jc[c]; k < sp->jc[c + 1]; ++k) {
        if (k >= sp->nir || sp->ir[k] >= var->dims[0])
          throw InvalidInput(fmt::format("\"{}\": sparse matrix {} is malformed", path, name));
        m(sp->ir[k], c) = values[k];
      }
    return m;
  }
  if (var->class_type != MAT_C_DOUBLE || var->data_type != MAT_T_DOUBLE)
    throw InvalidInput(fmt::format("\"{}\": matrix {} is not a double matrix", path, name));
  m = Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(var->data), rows, cols);
  return m;
}

std::string read_text(mat_t* mat, const char* name) {
  MatVar var(Mat_VarRead(mat, name));
  if (!var || var->class_type != MAT_C_CHAR) return {};
  std::string s;
  const std::size_t n = var->dims[0] * var->dims[1];
  if (var->data_type == MAT_T_UINT8 || var->data_type == MAT_T_UTF8) {
    s.assign(static_cast<const char*>(var->data), n);
  } else if (var->data_type == MAT_T_UINT16 || var->data_type == MAT_T_UTF16) {
    const auto* d = static_cast<const std::uint16_t*>(var->data);
    for (std::size_t i = 0; i < n; ++i) s.push_back(static_cast<char>(d[i] < 128 ? d[i] : '?'));
  }
  return s;
}

Eigen::MatrixXd require(mat_t* mat, const char* name, const std::string& path) {
  auto m = read_matrix(mat, name, path);
  if (!m) throw InvalidInput(fmt::format("\"{}\" has no matrix named {}", path, name));
  return *m;
}

void check_symmetric(const Eigen::MatrixXd& A, const char* name) {
  const double scale = A.cwiseAbs().maxCoeff();
  if ((A - A.transpose()).cwiseAbs().maxCoeff() > 1e-8 * scale)
    throw InvalidInput(fmt::format(
        "reduced model: {} is not symmetric (largest |{}_ij - {}_ji| = {:.3g} of its largest "
        "entry {:.3g})",
        name, name, name, (A - A.transpose()).cwiseAbs().maxCoeff() / scale, scale));
}

// Below this |omega^2| a mode is a rigid-body mode: 1e-10 of tr(K)/tr(M) of the model
// itself (without interface stiffness), a scale of its stiffest modes. A relative
// threshold on the eigenvalues of K + K_interface would grow with a stiff penalty and take
// low elastic modes for rigid ones.
double rigid_tolerance(const ReducedModel& m) {
  return 1e-10 * std::abs(m.K.diagonal().sum()) / m.M.diagonal().sum();
}

}  // namespace

void ReducedModel::validate() const {
  const Eigen::Index n = M.rows();
  auto need = [&](const Eigen::MatrixXd& m, Eigen::Index r, Eigen::Index c, const char* name) {
    if (m.rows() != r || m.cols() != c)
      throw InvalidInput(fmt::format("reduced model: {} is {} x {}, expected {} x {}", name,
                                     m.rows(), m.cols(), r, c));
    if (!m.allFinite())
      throw InvalidInput(fmt::format("reduced model: {} has a non-finite entry", name));
  };
  if (n == 0) throw InvalidInput("reduced model: M is empty");
  need(M, n, n, "M");
  need(K, n, n, "K");
  check_symmetric(M, "M");
  check_symmetric(K, "K");
  const auto ne = static_cast<Eigen::Index>(elements.size());
  need(Q, 3 * ne, n, "Q (element relative displacements)");
  need(T, n, 3 * ne, "T (element forces)");
  for (std::size_t e = 0; e < elements.size(); ++e)
    if (!(elements[e].area > 0))
      throw InvalidInput(
          fmt::format("reduced model: interface element {} has area {} m^2; each "
                      "element needs an area > 0",
                      e, elements[e].area));
  const auto nb = static_cast<Eigen::Index>(bolt_names.size());
  need(bolt_load, n, nb, "Fv (bolt loads)");
  need(bolt_elongation, nb, n, "bolt_elongation");
  if (bolt_axial_stiffness.size() != nb || bolt_preload.size() != nb)
    throw InvalidInput(
        "reduced model: bolt_axial_stiffness and bolt_preload need one value per bolt");
  need(recovery, 3 * static_cast<Eigen::Index>(output_names.size()), n, "R (recovery)");
  if (rough) {
    if (rough->pressure.size() != ne || !rough->pressure.allFinite() ||
        (rough->pressure.array() < 0.0).any() ||
        static_cast<Eigen::Index>(rough->in_contact.size()) != ne)
      throw InvalidInput(fmt::format(
          "reduced model: rough_pressure and rough_in_contact need one value per interface "
          "element ({}), pressures finite and >= 0",
          ne));
    for (const double v :
         {rough->E_star, rough->G_star, rough->H, rough->sigma, rough->R, rough->eta})
      if (!(v > 0.0) || !std::isfinite(v))
        throw InvalidInput(fmt::format(
            "reduced model: rough_surface [E*, G*, H, nu, sigma, R, eta, summit_sigma] has {}: "
            "E*, G*, H, sigma, R and eta must be finite and > 0",
            v));
  }
}

void write_reduced_model(const std::string& path, const ReducedModel& model) {
  model.validate();
  const std::filesystem::path target(path);
  const auto tmp = core::temporary_sibling(target, "mat");
  {
    MatFile mat(Mat_CreateVer(tmp.c_str(), nullptr, MAT_FT_MAT5));
    if (!mat) throw InvalidInput(fmt::format("cannot create \"{}\"", path));
    const auto ne = static_cast<Eigen::Index>(model.elements.size());
    Eigen::MatrixXd area(ne, 1), centroid(ne, 3), frame(ne, 9), which(ne, 1);
    std::vector<std::string> itf_names;
    for (Eigen::Index e = 0; e < ne; ++e) {
      const auto& el = model.elements[static_cast<std::size_t>(e)];
      area(e, 0) = el.area;
      centroid.row(e) = el.centroid.transpose();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) frame(e, 3 * r + c) = el.frame(r, c);
      auto it = std::find(itf_names.begin(), itf_names.end(), el.interface);
      if (it == itf_names.end()) it = itf_names.insert(itf_names.end(), el.interface);
      which(e, 0) = static_cast<double>(it - itf_names.begin());
    }
    write_text(mat.get(), "format", "asperity reduced model 1", path);
    write_matrix(mat.get(), "M", model.M, path);
    write_matrix(mat.get(), "K", model.K, path);
    write_matrix(mat.get(), "Q", model.Q, path);
    write_matrix(mat.get(), "T", model.T, path);
    write_matrix(mat.get(), "element_area", area, path);
    write_matrix(mat.get(), "element_centroid", centroid, path);
    write_matrix(mat.get(), "element_frame", frame, path);
    write_matrix(mat.get(), "element_interface", which, path);
    write_text(mat.get(), "interface_names", join_lines(itf_names), path);
    write_matrix(mat.get(), "Fv", model.bolt_load, path);
    write_matrix(mat.get(), "bolt_elongation", model.bolt_elongation, path);
    write_matrix(mat.get(), "bolt_axial_stiffness", model.bolt_axial_stiffness, path);
    write_matrix(mat.get(), "bolt_preload", model.bolt_preload, path);
    write_text(mat.get(), "bolt_names", join_lines(model.bolt_names), path);
    write_matrix(mat.get(), "R", model.recovery, path);
    write_text(mat.get(), "output_names", join_lines(model.output_names), path);
    write_matrix(mat.get(), "output_points", model.output_points, path);
    write_matrix(mat.get(), "fixed_interface_modes",
                 Eigen::MatrixXd::Constant(1, 1, static_cast<double>(model.fixed_interface_modes)),
                 path);
    if (const auto& r = model.rough) {
      Eigen::MatrixXd surface(1, 8);
      surface << r->E_star, r->G_star, r->H, r->nu, r->sigma, r->R, r->eta,
          r->summit_sigma ? 1.0 : 0.0;
      write_matrix(mat.get(), "rough_surface", surface, path);
      write_text(mat.get(), "rough_model", r->model, path);
      write_matrix(mat.get(), "rough_pressure", Eigen::MatrixXd(r->pressure), path);
      Eigen::MatrixXd touching(static_cast<Eigen::Index>(r->in_contact.size()), 1);
      for (Eigen::Index e = 0; e < touching.rows(); ++e)
        touching(e, 0) = r->in_contact[static_cast<std::size_t>(e)] ? 1.0 : 0.0;
      write_matrix(mat.get(), "rough_in_contact", touching, path);
      if (const auto& table = r->summit_heights) {
        const auto n = static_cast<Eigen::Index>(table->z_star().size());
        Eigen::MatrixXd heights(n, 2);
        for (Eigen::Index k = 0; k < n; ++k) {
          heights(k, 0) = table->z_star()[static_cast<std::size_t>(k)];
          heights(k, 1) = table->density_star()[static_cast<std::size_t>(k)];
        }
        write_matrix(mat.get(), "rough_summit_heights", heights, path);
      }
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, target, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InvalidInput(fmt::format("cannot write \"{}\"", path));
  }
}

ReducedModel read_reduced_model(const std::string& path) {
  core::require_regular_input(path, std::size_t{1} << 30, "reduced model");
  MatFile mat(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
  if (!mat)
    throw InvalidInput(fmt::format("\"{}\" is not a MATLAB .mat file (v5, v7 or v7.3)", path));
  ReducedModel m;
  m.source = path;
  m.M = require(mat.get(), "M", path);
  m.K = require(mat.get(), "K", path);
  const Eigen::Index n = m.M.rows();
  if (read_text(mat.get(), "format").rfind("asperity reduced model", 0) == 0) {
    m.Q = require(mat.get(), "Q", path);
    m.T = require(mat.get(), "T", path);
    const auto area = require(mat.get(), "element_area", path);
    const auto centroid = require(mat.get(), "element_centroid", path);
    const auto frame = require(mat.get(), "element_frame", path);
    const auto which = require(mat.get(), "element_interface", path);
    const auto names =
        split_lines(read_text(mat.get(), "interface_names"),
                    static_cast<std::size_t>(which.size() ? which.maxCoeff() + 1 : 0));
    for (Eigen::Index e = 0; e < area.rows(); ++e) {
      InterfaceElement el;
      el.area = area(e, 0);
      el.centroid = centroid.row(e).transpose();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) el.frame(r, c) = frame(e, 3 * r + c);
      el.interface = names.at(static_cast<std::size_t>(which(e, 0)));
      m.elements.push_back(el);
    }
    m.bolt_load = require(mat.get(), "Fv", path);
    m.bolt_elongation = require(mat.get(), "bolt_elongation", path);
    m.bolt_axial_stiffness = require(mat.get(), "bolt_axial_stiffness", path).col(0);
    m.bolt_preload = require(mat.get(), "bolt_preload", path).col(0);
    m.bolt_names = split_lines(read_text(mat.get(), "bolt_names"),
                               static_cast<std::size_t>(m.bolt_load.cols()));
    m.recovery = require(mat.get(), "R", path);
    m.output_points = require(mat.get(), "output_points", path);
    m.output_names = split_lines(read_text(mat.get(), "output_names"),
                                 static_cast<std::size_t>(m.output_points.rows()));
    m.fixed_interface_modes =
        static_cast<Eigen::Index>(require(mat.get(), "fixed_interface_modes", path)(0, 0));
    if (const auto surface = read_matrix(mat.get(), "rough_surface", path)) {
      if (surface->size() != 8)
        throw InvalidInput(fmt::format(
            "\"{}\": rough_surface has {} values, expected 8 (E*, G*, H, nu, sigma, R, eta, "
            "summit_sigma)",
            path, surface->size()));
      const Eigen::VectorXd v = surface->reshaped();
      RoughInterfaceRecord r{.E_star = v[0],
                             .G_star = v[1],
                             .H = v[2],
                             .nu = v[3],
                             .sigma = v[4],
                             .R = v[5],
                             .eta = v[6],
                             .summit_sigma = v[7] != 0.0,
                             .model = read_text(mat.get(), "rough_model"),
                             .pressure = require(mat.get(), "rough_pressure", path).reshaped(),
                             .in_contact = {}};
      const Eigen::MatrixXd touching = require(mat.get(), "rough_in_contact", path);
      for (Eigen::Index e = 0; e < touching.size(); ++e)
        r.in_contact.push_back(touching.reshaped()[e] != 0.0 ? 1 : 0);
      if (const auto heights = read_matrix(mat.get(), "rough_summit_heights", path)) {
        if (heights->cols() != 2)
          throw InvalidInput(
              fmt::format("\"{}\": rough_summit_heights is {} x {}; expected n x 2 (z*, phi*)",
                          path, heights->rows(), heights->cols()));
        const Eigen::VectorXd z = heights->col(0), p = heights->col(1);
        r.summit_heights = std::make_shared<const surface::SummitHeightTable>(
            std::vector<double>(z.begin(), z.end()), std::vector<double>(p.begin(), p.end()),
            fmt::format("rough_summit_heights of \"{}\"", path));
        if (!r.summit_sigma)
          throw InvalidInput(fmt::format(
              "\"{}\": rough_summit_heights needs rough_surface's summit_sigma = 1 (sigma the "
              "summit heights' standard deviation)",
              path));
      }
      m.rough = std::move(r);
    }
  } else {
    // The published Brake-Reuss beam layout.
    const Eigen::MatrixXd L = require(mat.get(), "L", path);
    const Eigen::MatrixXd Qm = require(mat.get(), "Qm", path);
    const Eigen::MatrixXd Tm = require(mat.get(), "Tm", path);
    const Eigen::Index ne = Qm.rows(), nn = Qm.cols();
    if (L.cols() != n || L.rows() < 3 * nn || Tm.rows() != nn || Tm.cols() != ne)
      throw InvalidInput(fmt::format(
          "\"{}\": L ({} x {}), Qm ({} x {}) and Tm ({} x {}) do not fit M ({} x {}): expected L "
          "with {} columns and at least 3 x {} rows, Tm {} x {}",
          path, L.rows(), L.cols(), Qm.rows(), Qm.cols(), Tm.rows(), Tm.cols(), n, n, n, nn, nn,
          ne));
    const Eigen::MatrixXd Li = L.topRows(3 * nn);
    m.Q = Eigen::MatrixXd::Zero(3 * ne, n);
    m.T = Eigen::MatrixXd::Zero(n, 3 * ne);
    for (Eigen::Index e = 0; e < ne; ++e)
      for (Eigen::Index j = 0; j < nn; ++j) {
        if (Qm(e, j) != 0.0)
          for (int k = 0; k < 3; ++k) m.Q.row(3 * e + k) += Qm(e, j) * Li.row(3 * j + k);
        if (Tm(j, e) != 0.0)
          for (int k = 0; k < 3; ++k)
            m.T.col(3 * e + k) += Tm(j, e) * Li.row(3 * j + k).transpose();
      }
    for (Eigen::Index e = 0; e < ne; ++e) {
      InterfaceElement el;
      el.interface = "interface";
      el.area = Tm.col(e).sum();
      el.centroid = Eigen::Vector3d::Constant(std::nan(""));
      m.elements.push_back(el);
    }
    m.bolt_load = require(mat.get(), "Fv", path);
    m.bolt_elongation = Eigen::MatrixXd::Zero(m.bolt_load.cols(), n);
    m.bolt_axial_stiffness = Eigen::VectorXd::Zero(m.bolt_load.cols());
    m.bolt_preload = Eigen::VectorXd::Zero(m.bolt_load.cols());
    for (Eigen::Index b = 0; b < m.bolt_load.cols(); ++b)
      m.bolt_names.push_back(fmt::format("Fv[{}]", b));
    if (auto R = read_matrix(mat.get(), "R", path)) {
      m.recovery = *R;
      if (m.recovery.rows() % 3 != 0)
        m.recovery.conservativeResize(m.recovery.rows() - m.recovery.rows() % 3, Eigen::NoChange);
      for (Eigen::Index p = 0; p < m.recovery.rows() / 3; ++p)
        m.output_names.push_back(fmt::format("R[{}]", p));
      m.output_points = Eigen::MatrixXd::Constant(m.recovery.rows() / 3, 3, std::nan(""));
    } else {
      m.recovery = Eigen::MatrixXd::Zero(0, n);
      m.output_points = Eigen::MatrixXd::Zero(0, 3);
    }
  }
  try {
    m.validate();
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("\"{}\": {}", path, e.what()));
  }
  return m;
}

LinearModesResult reduced_linear_modes(const ReducedModel& model, const Eigen::VectorXd& k_e,
                                       int count, const std::string& label) {
  Eigen::MatrixXd K = model.K;
  if (k_e.size() != model.Q.rows())
    throw InvalidInput(fmt::format("{}: {} interface stiffnesses for {} element DOFs", label,
                                   k_e.size(), model.Q.rows()));
  if (k_e.any()) {
    Eigen::VectorXd kA(k_e.size());
    for (Eigen::Index i = 0; i < k_e.size(); ++i)
      kA[i] = k_e[i] * model.elements[static_cast<std::size_t>(i / 3)].area;
    K += model.Q.transpose() * kA.asDiagonal() * model.Q;
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, model.M);
  if (es.info() != Eigen::Success)
    throw NumericalError(
        fmt::format("{}: the eigenvalues of the reduced model ({} DOFs) failed "
                    "(dense generalized symmetric solver; M positive definite?)",
                    label, K.rows()));
  const Eigen::VectorXd w2 = es.eigenvalues();
  const double tol = rigid_tolerance(model);
  LinearModesResult out;
  std::vector<Eigen::Index> elastic;
  for (Eigen::Index i = 0; i < w2.size(); ++i) {
    if (std::abs(w2[i]) <= tol)
      ++out.rigid_body_modes;
    else if (w2[i] < 0)
      throw InvalidInput(
          fmt::format("{}: the stiffness is not positive semi-definite (omega^2 = "
                      "{:.4g} rad^2/s^2): a negative stiffness in the model",
                      label, w2[i]));
    else
      elastic.push_back(i);
  }
  if (out.rigid_body_modes > 6)
    throw InvalidInput(fmt::format(
        "{}: {} rigid-body modes, more than a free-free structure allows (6): the bodies are not "
        "held together (no bolt or closed interface between them)",
        label, out.rigid_body_modes));
  const auto n = std::min<std::size_t>(elastic.size(), static_cast<std::size_t>(count));
  out.frequency_hz.resize(static_cast<Eigen::Index>(n));
  out.shapes.resize(K.rows(), static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    out.frequency_hz[static_cast<Eigen::Index>(i)] =
        std::sqrt(w2[elastic[i]]) / (2 * std::numbers::pi);
    out.shapes.col(static_cast<Eigen::Index>(i)) = es.eigenvectors().col(elastic[i]);
  }
  return out;
}

Eigen::MatrixXd read_mat_matrix(const std::string& path, const std::string& name) {
  core::require_regular_input(path, std::size_t{1} << 30, "MATLAB file");
  MatFile mat(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
  if (!mat)
    throw InvalidInput(fmt::format("\"{}\" is not a MATLAB .mat file (v5, v7 or v7.3)", path));
  return require(mat.get(), name.c_str(), path);
}

LinearPrestress linear_prestress(const ReducedModel& model, double k_n) {
  if (!(k_n > 0))
    throw InvalidInput(fmt::format("normal_stiffness = {} Pa/m: give a value > 0", k_n));
  const Eigen::Index n = model.dofs();
  const auto ne = static_cast<Eigen::Index>(model.elements.size());
  // Pretension (Abaqus *PRE-TENSION SECTION): the shanks' axial stiffness is replaced by
  // their preloads.
  Eigen::MatrixXd K0 = model.K;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  for (Eigen::Index b = 0; b < model.bolt_load.cols(); ++b) {
    const Eigen::RowVectorXd h = model.bolt_elongation.row(b);
    K0 -= model.bolt_axial_stiffness[b] * h.transpose() * h;
    f += model.bolt_preload[b] * model.bolt_load.col(b);
  }
  // Rigid-body motion carries no load (the preloads are self-equilibrated): a term
  // alpha M r r^T M on the rigid-body modes r of (K0 + contact, M) makes the solve regular
  // without changing the answer.
  LinearPrestress out;
  out.in_contact.assign(static_cast<std::size_t>(ne), 1);
  for (out.iterations = 1; out.iterations <= 100; ++out.iterations) {
    Eigen::MatrixXd Ke = K0;
    for (Eigen::Index e = 0; e < ne; ++e)
      if (out.in_contact[static_cast<std::size_t>(e)]) {
        const Eigen::RowVectorXd q = model.Q.row(3 * e + 2);
        Ke += k_n * model.elements[static_cast<std::size_t>(e)].area * q.transpose() * q;
      }
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Ke, model.M);
    const Eigen::VectorXd w2 = es.eigenvalues();
    const double tol = rigid_tolerance(model);
    Eigen::MatrixXd Kr = Ke;
    const double alpha = w2.cwiseAbs().maxCoeff() * 1e-3;
    for (Eigen::Index i = 0; i < w2.size(); ++i)
      if (std::abs(w2[i]) <= tol) {
        const Eigen::VectorXd mr = model.M * es.eigenvectors().col(i);
        Kr += alpha * mr * mr.transpose();
      }
    // The penalty makes Kr ill-conditioned: one step of iterative refinement brings the
    // equilibrium (interface force = bolt load) from ~1e-4 to round-off.
    const auto ldlt = Kr.ldlt();
    out.x = ldlt.solve(f);
    out.x += ldlt.solve(f - Kr * out.x);
    std::vector<char> next(static_cast<std::size_t>(ne), 0);
    bool changed = false;
    for (Eigen::Index e = 0; e < ne; ++e) {
      const double gap = model.Q.row(3 * e + 2).dot(out.x);
      next[static_cast<std::size_t>(e)] = gap < 0;
      changed = changed ||
                next[static_cast<std::size_t>(e)] != out.in_contact[static_cast<std::size_t>(e)];
    }
    if (!changed) break;
    out.in_contact = next;
  }
  if (out.iterations > 100)
    throw NumericalError("linear prestress: the contact set did not settle in 100 iterations");
  out.pressure = Eigen::VectorXd::Zero(ne);
  for (Eigen::Index e = 0; e < ne; ++e)
    if (out.in_contact[static_cast<std::size_t>(e)]) {
      out.pressure[e] = std::max(0.0, -k_n * model.Q.row(3 * e + 2).dot(out.x));
      out.contact_area += model.elements[static_cast<std::size_t>(e)].area;
    }
  return out;
}

}  // namespace asperity::fem
