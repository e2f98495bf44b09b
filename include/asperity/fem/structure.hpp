#pragma once
// A bolted structure from a case file to a reduced model and its linear modes: the steps
// of `asperity structure` (beyond the thesis). See docs/structures.md for the case format.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "asperity/fem/bolt.hpp"
#include "asperity/fem/elasticity.hpp"
#include "asperity/fem/fixture.hpp"
#include "asperity/fem/gap_map.hpp"
#include "asperity/fem/geometry.hpp"
#include "asperity/fem/interface.hpp"
#include "asperity/fem/mesh.hpp"
#include "asperity/fem/reduced_model.hpp"
#include "asperity/fem/reduction.hpp"
#include "asperity/fem/rough_prestress.hpp"

namespace asperity::fem {

/// An interface of the case with its linear contact stiffnesses (analyses b and c).
struct StructureInterface {
  InterfaceSpec spec;
  double normal_stiffness = 0.0;      ///< linear normal penalty [Pa/m] (> 0)
  double tangential_stiffness = 0.0;  ///< stuck tangential stiffness [Pa/m] (> 0)
};

/// The rough surfaces of the interfaces ([rough_contact]): the thesis's rough flat (chapter 4)
/// as their normal law under the bolt preloads and their stiffness about that prestress.
/// E*, G* and nu come from the bodies' materials; one rough surface for all interfaces.
struct RoughContactCase {
  bool given = false;
  double hardness = 0.0;      ///< H of the softer body [Pa]
  double sigma = 0.0;         ///< combined rms roughness [m] (or of the summits: summit_sigma)
  bool summit_sigma = false;  ///< sigma is the summit heights' standard deviation
  std::string surface_data;   ///< MATLAB file with Re, area_density, z_max, normzinterp, pzinterp
  std::string summit_heights_file;  ///< CSV summit-height table (height, density)
  /// Its summit-height density, summed over as such (null: Gaussian of sigma; also with
  /// summit_distribution = "gaussian").
  std::shared_ptr<const surface::SummitHeightTable> heights;
  double R = 0.0;    ///< mean asperity radius [m]
  double eta = 0.0;  ///< asperities per unit area [1/m^2]
  contact::ModelName model = contact::ModelName::bke;
  std::string gap_map;  ///< MATLAB file with a P x 3 (x, y, gap) grid; empty: no gap
  std::string gap_variable = "mesoscale_xygap";
  std::optional<GapMap> gap;  ///< read with the case (its errors are the case's)
  Eigen::Vector3d gap_origin = Eigen::Vector3d::Zero();  ///< where the map's (0, 0) lies [m]
};

/// The thesis's fretting apparatus around the structure's joint ([fretting]: section 5.2,
/// Fig. 5.7; docs/structures.md): grips, the actuator's compliance, the imposed tip
/// amplitudes and the bolt preloads to run them at. Needs [rough_contact].
struct FrettingCase {
  bool given = false;
  Fixture fixture;
  std::vector<double> tip_amplitudes;  ///< Delta_0 at the actuator's tip [m], ascending, > 0
  /// Sums of the bolt preloads to run at [N], each shared among the bolts in proportion to
  /// their [[bolt]] preloads; empty: the [[bolt]] preloads as given.
  std::vector<double> total_preloads;
  int harmonics = 15;             ///< harmonic balance at omega = 0: harmonics 0..H
  std::size_t time_points = 256;  ///< N_t
};

struct OutputPoint {
  std::string name;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< [m]
};

/// A structure case: geometry (meshed by gmsh) or a mesh file, one material per body,
/// interfaces, bolts, output points, reduction settings.
struct StructureCase {
  std::string path;  ///< the case file (messages, relative paths)
  std::string name;
  Geometry geometry;       ///< used when mesh_file is empty
  std::string mesh_file;   ///< .msh or .inp, relative to the case file
  double mesh_unit = 1.0;  ///< length of one mesh-file unit [m] ([mesh] unit)
  std::vector<std::string> body_names;
  std::vector<IsotropicMaterial> body_materials;  ///< per body_names
  std::vector<StructureInterface> interfaces;
  std::vector<BoltSpec> bolts;
  std::vector<OutputPoint> outputs;
  ReductionOptions reduction;
  RoughContactCase rough;
  FrettingCase fretting;
  int modes = 10;  ///< elastic modes reported per linear analysis
};

/// Reads a structure case file (TOML); InvalidInput names the key and line.
[[nodiscard]] StructureCase read_structure_case(const std::string& path);

struct StepCost {
  std::string step;
  double seconds = 0.0;
  double peak_rss_mib = 0.0;  ///< the process's peak resident memory after the step
};

/// The process's peak resident memory so far [MiB] (getrusage's ru_maxrss): what a
/// StepCost records after its step.
[[nodiscard]] double peak_resident_memory_mib();

struct LinearAnalysis {
  std::string name;  ///< "open", "frictionless", "stuck"
  LinearModesResult modes;
};

struct StructureResult {
  Mesh mesh;  ///< nodes split per body
  std::size_t shared_nodes_split = 0;
  std::vector<Interface> interfaces;
  std::vector<Bolt> bolts;
  CraigBampton reduction;
  ReducedModel model;
  LinearPrestress prestress;             ///< frictionless, linear normal penalty
  double bolt_load_total = 0.0;          ///< sum of preloads [N]
  std::vector<LinearAnalysis> analyses;  ///< open, frictionless, stuck (and rough)
  std::optional<RoughPrestress> rough;   ///< with [rough_contact]
  Eigen::VectorXd gap;                   ///< per element [m] (empty without a gap map)
  std::vector<StepCost> costs;
  double total_mass = 0.0;  ///< [kg] bodies (elements) only
};

struct StructureOptions {
  MeshOptions meshing;
  /// Called with the name of each step as it starts (the CLI prints them on stderr).
  std::function<void(const std::string&)> progress;
};

/// The structure before reduction: meshed, assembled (K and M with the bolts' shanks), bolts
/// and interfaces placed.
struct AssembledStructure {
  Mesh mesh;  ///< nodes split per body
  std::size_t shared_nodes_split = 0;
  Eigen::SparseMatrix<double> K, M;
  std::vector<Interface> interfaces;
  std::vector<Bolt> bolts;
  double bolt_load_total = 0.0;  ///< sum of preloads [N]
  double total_mass = 0.0;       ///< [kg] bodies (elements) only
  std::vector<StepCost> costs;   ///< mesh, assembly, bolts and interfaces
};

/// Mesh (or read the mesh), assemble, place the bolts and interfaces.
[[nodiscard]] AssembledStructure assemble_structure(const StructureCase& c,
                                                    const StructureOptions& options = {});

/// The case's rough surfaces ([rough_contact]) as the normal law of the model's interface
/// under its bolt preloads (rough_prestress), recorded in model.rough with each element's
/// prestress pressure. `gap`: per element [m] or empty.
RoughPrestress apply_rough_contact(const StructureCase& c, ReducedModel& model,
                                   const Eigen::VectorXd& gap);

/// Mesh, assemble, place bolts and interfaces, reduce, prestress and linear modes.
[[nodiscard]] StructureResult run_structure(const StructureCase& c,
                                            const StructureOptions& options = {});

}  // namespace asperity::fem
