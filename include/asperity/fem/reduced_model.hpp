#pragma once
// A reduced structural model with zero-thickness interface elements: what
// `asperity structure` writes and a vibration case reads (SI units throughout).
//
// File format (MATLAB v5 .mat, written and read with matio, BSD-2-Clause: MATLAB's `load`
// and scipy.io.loadmat open it with no extra package; v5 keeps every matrix in one file
// with names, and the models are small: ~1000 DOFs):
//   format                  char  "asperity reduced model 1"
//   M, K                    n x n       reduced mass [kg] and stiffness [N/m] (free-free)
//   Q                       3N x n      element relative displacements (t1, t2, n) [m]
//   T                       n x 3N      element tractions [Pa] -> reduced forces [N]
//   element_area            N x 1       [m^2]
//   element_centroid        N x 3       [m]
//   element_frame           N x 9       rows t1, t2, n of each element, row-major
//   element_interface       N x 1       0-based index into interface_names
//   interface_names         char        one name per line
//   Fv                      n x B       reduced force of a unit tension of each bolt [N/N]
//   bolt_elongation         B x n       shank elongation row [m per unit x]
//   bolt_axial_stiffness    B x 1       E A / L [N/m]
//   bolt_preload            B x 1       [N]
//   bolt_names              char        one per line
//   R                       3P x n      displacement (x, y, z) of each output point [m]
//   output_names            char        one per line
//   output_points           P x 3       [m]
//   fixed_interface_modes   1 x 1       modes of the tied structure kept
// Reduced models made elsewhere are read from the published Brake-Reuss beam layout
// (M, K, Fv, L, Qm, Tm and optionally R: element displacements kron(Qm, I3) L[:3n_nodes]
// and forces L[:3n_nodes]^T kron(Tm, I3), element areas the column sums of Tm) and from
// MatrixMarket files (M and K only).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "asperity/surface/summit_heights.hpp"

namespace asperity::fem {

struct InterfaceElement {
  std::string interface;
  double area = 0.0;                                    ///< [m^2]
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();   ///< [m] (NaN when unknown)
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();  ///< rows t1, t2, n
};

/// The rough interface of `asperity structure`'s [rough_contact] (combined values, SI) and
/// each element's nominal pressure and contact state at the rough prestress: what a
/// vibration case needs to put rough_contact elements on every interface element.
struct RoughInterfaceRecord {
  double E_star = 0.0, G_star = 0.0, H = 0.0, nu = 0.0;  ///< [Pa], [Pa], [Pa], [-]
  double sigma = 0.0;  ///< [m]: rms roughness, or of the summit heights if summit_sigma
  double R = 0.0;      ///< mean asperity radius [m]
  double eta = 0.0;    ///< areal density of asperities [1/m^2]
  bool summit_sigma = false;
  /// The measured summit-height density summed over (null: Gaussian); written as
  /// rough_summit_heights [z*, phi*] (standardized, surface::SummitHeightTable).
  std::shared_ptr<const surface::SummitHeightTable> summit_heights;
  std::string model;         ///< asperity model name ("bke", ...)
  Eigen::VectorXd pressure;  ///< per element [Pa]
  /// Per element: at least one asperity expected in contact, eta A Phi(d) >= 1
  /// (RoughPrestress::in_contact): the elements the rough linear modes stiffen.
  std::vector<char> in_contact;
};

struct ReducedModel {
  Eigen::MatrixXd M, K;
  Eigen::MatrixXd Q;  ///< 3N x n
  Eigen::MatrixXd T;  ///< n x 3N
  std::vector<InterfaceElement> elements;
  Eigen::MatrixXd bolt_load;        ///< n x B (Fv)
  Eigen::MatrixXd bolt_elongation;  ///< B x n
  Eigen::VectorXd bolt_axial_stiffness, bolt_preload;
  std::vector<std::string> bolt_names;
  Eigen::MatrixXd recovery;  ///< 3P x n
  std::vector<std::string> output_names;
  Eigen::MatrixXd output_points;  ///< P x 3
  Eigen::Index fixed_interface_modes = 0;
  std::string source;                         ///< where it came from (a file, `asperity structure`)
  std::optional<RoughInterfaceRecord> rough;  ///< with [rough_contact]

  [[nodiscard]] Eigen::Index dofs() const { return M.rows(); }
  /// Throws InvalidInput naming the matrix: sizes that do not agree, non-finite entries,
  /// M or K not symmetric (1e-8 of the largest entry), an element with zero area.
  void validate() const;
};

void write_reduced_model(const std::string& path, const ReducedModel& model);
/// Reads an asperity .mat or a published-layout .mat (see above); InvalidInput names the
/// file and the missing or malformed matrix.
[[nodiscard]] ReducedModel read_reduced_model(const std::string& path);

/// A real 2-D matrix (full or sparse) named `name` in a MATLAB v5 file, as doubles;
/// InvalidInput names the file and the variable when it is absent or not a real matrix.
[[nodiscard]] Eigen::MatrixXd read_mat_matrix(const std::string& path, const std::string& name);

/// Elastic modes of a reduced model with a linear interface stiffness per element and
/// direction (k_e, 3N values, N/m; zero where the interface is open).
struct LinearModesResult {
  Eigen::VectorXd frequency_hz;  ///< elastic modes only, ascending
  Eigen::MatrixXd shapes;        ///< reduced, mass-normalised, one column per elastic mode
  Eigen::Index rigid_body_modes = 0;
};
/// `label` names the analysis in messages. Rigid-body modes: |omega^2| below 1e-10 of
/// tr(K)/tr(M) of the model. Throws InvalidInput when there are more than 6 of them (more
/// than a free-free structure allows).
[[nodiscard]] LinearModesResult reduced_linear_modes(const ReducedModel& model,
                                                     const Eigen::VectorXd& element_stiffness,
                                                     int count, const std::string& label);

/// The bolt preloads on a frictionless interface with a linear normal penalty k_n [Pa/m]
/// (elements in tension open: active set). Pressure per element [Pa] (>= 0), the reduced
/// static displacement, and the contact state.
struct LinearPrestress {
  Eigen::VectorXd x;
  Eigen::VectorXd pressure;      ///< N
  std::vector<char> in_contact;  ///< N
  double contact_area = 0.0;     ///< [m^2]
  int iterations = 0;
};
[[nodiscard]] LinearPrestress linear_prestress(const ReducedModel& model, double normal_stiffness);

}  // namespace asperity::fem
