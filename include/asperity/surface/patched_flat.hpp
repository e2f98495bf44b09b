#pragma once
// A rough flat whose nominal area is divided into patches, each a rough flat (chapter 4)
// at its own local pressure: the interface of a bolted joint under a non-uniform pressure
// field (joint/interface.hpp). The patches share the materials and roughness, so in the
// normalized variables of rough_flat.hpp they differ only in their separation d*_i (from
// their own P*_i = P_i/(K H A_i)) and their share of the nominal area w_i = A_i/A0. For a
// common tangential displacement delta* the virgin curve is
//   Q*_l(delta*) = sum_i w_i Q*_l(delta*; d*_i)          (forces over K H A0)
// and, Masing's rules being linear in the backbone (hysteresis/sum_backbone.hpp), the
// joint's response to any history is that of this one backbone. It is tabulated once,
// from the same one-pass asperity sums as RoughFlatBackbone (summed sample by sample),
// with the same verified error bound.
#include <vector>

#include "asperity/hysteresis/tabulated_backbone.hpp"
#include "asperity/surface/rough_flat.hpp"

namespace asperity::surface {

/// One patch: its share of the nominal area A_i/A0 (> 0) and its separation d*.
struct FlatPatch {
  double weight = 0.0;
  double d_star = 0.0;
};

/// Per-patch quantities of a PatchedRoughFlatBackbone (forces over K H A0, lengths over
/// sigma_s; the patch's weight included).
struct FlatPatchResponse {
  double static_friction_star = 0.0;  ///< w_i Q*_max(d*_i)
  double stiffness_star = 0.0;        ///< w_i dQ*_l/d delta* at 0
  /// delta* from which every asperity of the patch slips (its own table end: Q_l equals
  /// its Q_max to < 1e-12 beyond): the patch is in gross slip there.
  double gross_slip_star = 0.0;
};

class PatchedRoughFlatBackbone final : public hysteresis::TabulatedBackbone {
 public:
  /// Patches whose d* agree to 1e-12 (relative) share one asperity sum (a symmetric or
  /// uniform field costs one sum per distinct pressure). One patch of weight 1 gives
  /// exactly RoughFlatBackbone(flat, d*). Throws InvalidInput for no patch, a weight
  /// <= 0 or a non-finite d*, or a patch that carries no friction force.
  ///
  /// `series_compliance_star` C* >= 0 (a compliance over sigma_s/(K H A0)) puts a linear
  /// spring in series with the interface (the joint halves, joint/interface.hpp): the
  /// table is then Q*(x*) with x* = x*_i + C* Q*_l(x*_i) (x*_i the interface's own
  /// displacement), dQ*/dx* = Q*_l'/(1 + C* Q*_l'), d2Q*/dx*2 = Q*_l''/(1 + C* Q*_l')^3.
  /// A linear spring in series with a Masing element is a Masing element with this
  /// backbone (every branch: Delta x = 2 x_l(Delta Q/2) + C Delta Q). gross_slip_star
  /// is then in x* too.
  PatchedRoughFlatBackbone(const RoughFlat& flat, const std::vector<FlatPatch>& patches,
                           double rel_tol = 1e-9, double series_compliance_star = 0.0);

  [[nodiscard]] const std::vector<FlatPatch>& patches() const { return patches_; }
  [[nodiscard]] const std::vector<FlatPatchResponse>& responses() const { return responses_; }
  /// Number of distinct asperity sums the table was built from.
  [[nodiscard]] std::size_t distinct_sums() const { return distinct_; }

 private:
  struct Built;
  static Built build(const RoughFlat& flat, const std::vector<FlatPatch>& patches, double rel_tol,
                     double series_compliance_star);
  PatchedRoughFlatBackbone(Built&& b, const std::vector<FlatPatch>& patches);
  std::vector<FlatPatch> patches_;
  std::vector<FlatPatchResponse> responses_;
  std::size_t distinct_ = 0;
};

}  // namespace asperity::surface
