#pragma once
// Quasi-static fretting of a finite-element joint in the thesis's apparatus (chapter 5:
// section 5.2, Fig. 5.7; beyond the thesis, which models the interface alone): the
// actuator's tip moves Delta(theta) = Delta_0 sin(theta), the gripped joint
// (fem::condense_gripped) with a rough-contact element on every interface element in contact
// answers with its steady cycle. The cycle is periodic in theta and rate-independent, so it
// is the harmonic-balance problem at omega = 0:
//   K x(theta) + sum_e T_e^T f_e(T_e x)(theta) = e_z k Delta(theta),
// solved for the Fourier coefficients of x (harmonics 0..H, AFT on N_t samples) by Newton's
// method with the analytic Jacobian, continued from the smallest amplitude up. From x: the
// joint displacement delta = z (the laser sensor on the driven end) and the load cell's
// force Q = k (Delta - z), sampled over the cycle; the energy lost per cycle is the loop's
// area, W = closed integral Q d delta (Eq. 4.16's definition).
#include <vector>

#include <Eigen/Dense>

#include "asperity/fem/fixture.hpp"
#include "asperity/fem/structure.hpp"
#include "asperity/vibration/elements.hpp"

namespace asperity::vibration {

struct QuasiStaticFrettingOptions {
  int harmonics = 15;             ///< harmonics 0..H kept, H in [1, 64]
  std::size_t time_points = 256;  ///< N_t: even, >= 2 H + 2
  /// Newton: |R| <= tolerance k Delta_0, in [1e-14, 1e-3). Where an element's traction
  /// reaches its 2-D limit the rough-contact law's periodic response can jump by a few
  /// hundredths of a newton under an infinitesimal change of the path (docs/rough_contact.md,
  /// "Limits"); no Newton iterate gets below that jump. Measured on the two-block example
  /// near gross slip: the residual stalls at 2.1e-6 of k Delta_0. 1e-5 of the drive's force
  /// (13 mN at a 35 um tip on 38 N/um) is the default; the residual reached is reported.
  double tolerance = 1e-5;
  int max_iterations = 50;  ///< per amplitude, >= 1
  void validate() const;
};

struct FrettingCycle {
  double tip_amplitude = 0.0;           ///< Delta_0 [m]
  double force_amplitude = 0.0;         ///< (max Q - min Q)/2 over the cycle [N]
  double displacement_amplitude = 0.0;  ///< (max delta - min delta)/2 [m]
  double energy = 0.0;  ///< W = closed integral Q d delta [J] (> 0 for a joint that slips)
  /// Samples of the cycle at theta_i = 2 pi i / N_t [m], [N].
  Eigen::VectorXd delta, force;
  int iterations = 0;
  double residual = 0.0;  ///< |R| / (k Delta_0) at the end
};

struct QuasiStaticFretting {
  /// dQ/d delta of the joint with every element stuck at the prestress (the elements'
  /// initial stiffness): the stiffness a small cycle's loop starts with [N/m].
  double stiffness = 0.0;
  std::vector<FrettingCycle> cycles;  ///< one per tip amplitude, in the order given
};

/// `elements` act on the joint's coordinates (e.g. interface_rough_contact of its model).
/// Tip amplitudes are > 0 and finite. Throws InvalidInput for bad options or amplitudes,
/// NumericalError (with the amplitude, the residual reached and what to try) when Newton's
/// method does not converge.
[[nodiscard]] QuasiStaticFretting quasi_static_fretting(
    const fem::GrippedJoint& joint, const std::vector<PlacedElement>& elements,
    const std::vector<double>& tip_amplitudes, const QuasiStaticFrettingOptions& options = {});

/// One bolt preload of a structure's fretting run.
struct PreloadFretting {
  double total_preload = 0.0;  ///< sum of the bolts' preloads [N]
  fem::RoughPrestress prestress;
  std::size_t elements_in_contact = 0;  ///< those given a rough-contact element
  QuasiStaticFretting fretting;
  /// d ln W / d ln Q_0 between successive cycles (one fewer than the cycles): the
  /// energy-force exponent (Fig. 6.12-6.14 read it from the same pairs); NaN where a
  /// cycle dissipates nothing or the force does not grow.
  std::vector<double> exponents;
};

/// A structure case with [fretting] in its apparatus: the bodies condensed onto the
/// interface, drive and bolt coordinates (fem::condense_gripped), then per total preload
/// the rough prestress and the quasi-static cycles at the tip amplitudes.
struct StructureFretting {
  Eigen::Index mesh_nodes = 0, mesh_dofs = 0;
  std::size_t interface_elements = 0, held_nodes = 0, driven_nodes = 0;
  double total_mass = 0.0;  ///< [kg]
  std::vector<PreloadFretting> runs;
  std::vector<fem::StepCost> costs;
};

/// Throws InvalidInput when the case has no [fretting] (or no [rough_contact]), and what
/// its steps throw.
[[nodiscard]] StructureFretting structure_fretting(const fem::StructureCase& c,
                                                   const fem::StructureOptions& options = {});

}  // namespace asperity::vibration
