#pragma once
// A bolted structure from a case file to a reduced model and its linear modes: the steps
// of `asperity structure` (beyond the thesis). See docs/structures.md for the case format.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "asperity/fem/bolt.hpp"
#include "asperity/fem/elasticity.hpp"
#include "asperity/fem/geometry.hpp"
#include "asperity/fem/interface.hpp"
#include "asperity/fem/mesh.hpp"
#include "asperity/fem/reduced_model.hpp"
#include "asperity/fem/reduction.hpp"

namespace asperity::fem {

/// An interface of the case with its linear contact stiffnesses (analyses b and c).
struct StructureInterface {
  InterfaceSpec spec;
  double normal_stiffness = 0.0;      ///< linear normal penalty [Pa/m] (> 0)
  double tangential_stiffness = 0.0;  ///< stuck tangential stiffness [Pa/m] (> 0)
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
  int modes = 10;  ///< elastic modes reported per linear analysis
};

/// Reads a structure case file (TOML); InvalidInput names the key and line.
[[nodiscard]] StructureCase read_structure_case(const std::string& path);

struct StepCost {
  std::string step;
  double seconds = 0.0;
  double peak_rss_mib = 0.0;  ///< the process's peak resident memory after the step
};

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
  std::vector<LinearAnalysis> analyses;  ///< open, frictionless, stuck
  std::vector<StepCost> costs;
  double total_mass = 0.0;  ///< [kg] bodies (elements) only
};

struct StructureOptions {
  MeshOptions meshing;
  /// Called with the name of each step as it starts (the CLI prints them on stderr).
  std::function<void(const std::string&)> progress;
};

/// Mesh, assemble, place bolts and interfaces, reduce, prestress and linear modes.
[[nodiscard]] StructureResult run_structure(const StructureCase& c,
                                            const StructureOptions& options = {});

}  // namespace asperity::fem
