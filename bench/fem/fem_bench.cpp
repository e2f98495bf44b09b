// Benchmarks of the finite-element layer (issue 19): the Craig-Bampton reduction of a
// mid-size bolted structure, examples/structures/two_blocks.toml meshed finer than the
// example (global 5 mm, interface 2.5 mm, holes 2 mm) with 32 patches,
// against references measured in the same run on the same matrices:
//  - the assembly of K and M (what a reduction costs in assemblies);
//  - one sparse factorisation of the tied structure's stiffness (SimplicialLDLT, AMD),
//    what any reduction needs at least once.
// Each reduction's phases (reduction.cpp: ordering, factorisation, constraint solves,
// interface flexibility, fixed-interface modes and load responses, load vectors, reduced
// matrices) are printed from its last run.
// The Brake-Reuss beam (95,247 DOFs, 200 patches) takes minutes and is not run here:
//   /usr/bin/time -v build/ci/src/cli/asperity structure examples/brb/brb.toml
//     --out /tmp/brb --json > /tmp/brb.json   (one command line)
// prints the peak memory; the JSON's "costs" hold the time and peak memory per step
// (docs/performance.md).
// Needs the gmsh program (apt-get install gmsh) to mesh the blocks once.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include <Eigen/SparseCholesky>

#include "../ratio_reporter.hpp"
#include "asperity/fem/structure.hpp"

#ifndef ASPERITY_SOURCE_DIR
#define ASPERITY_SOURCE_DIR "."
#endif

namespace {

using namespace asperity;

struct Blocks {
  fem::StructureCase c;
  fem::Mesh mesh;
  std::vector<fem::IsotropicMaterial> materials;
  fem::StiffnessAndMass km;
  std::vector<fem::Interface> interfaces;
  std::vector<Eigen::VectorXd> bolt_loads;
};

const Blocks& blocks() {
  static const Blocks b = [] {
    Blocks s;
    s.c = fem::read_structure_case(std::string(ASPERITY_SOURCE_DIR) +
                                   "/examples/structures/two_blocks.toml");
    s.c.geometry.size.global = 5e-3;
    s.c.geometry.size.interface = 2.5e-3;
    s.c.geometry.size.hole = 2e-3;
    s.c.interfaces.front().spec.patches = 32;
    s.mesh = fem::mesh_geometry(s.c.geometry);
    for (const auto& name : s.mesh.bodies)
      for (std::size_t i = 0; i < s.c.body_names.size(); ++i)
        if (s.c.body_names[i] == name) s.materials.push_back(s.c.body_materials[i]);
    (void)fem::split_shared_nodes(s.mesh);
    const auto faces = fem::boundary_faces(s.mesh);
    s.km = fem::assemble(s.mesh, s.materials);
    const Eigen::Index dofs = 3 * s.mesh.node_count();
    for (const auto& spec : s.c.bolts) {
      const auto bolt = fem::place_bolt(s.mesh, faces, spec);
      s.km.K += fem::bolt_stiffness(bolt, dofs);
      s.km.M += fem::bolt_mass(bolt, dofs);
      s.bolt_loads.push_back(-Eigen::VectorXd(bolt.elongation));
    }
    for (const auto& si : s.c.interfaces)
      s.interfaces.push_back(fem::build_interface(s.mesh, faces, si.spec));
    std::fprintf(stderr, "two blocks, refined: %ld nodes, %zu elements, %ld DOFs, %zu patches\n",
                 static_cast<long>(s.mesh.node_count()), s.mesh.element_count(),
                 static_cast<long>(dofs), s.interfaces.front().patches.size());
    return s;
  }();
  return b;
}

fem::CraigBampton g_last;

void BM_CraigBamptonBlocks(benchmark::State& state) {
  const auto& b = blocks();
  for (auto _ : state) {
    g_last =
        fem::craig_bampton(b.km.K, b.km.M, b.mesh.nodes, b.interfaces, b.c.reduction, b.bolt_loads);
    benchmark::DoNotOptimize(g_last.K.data());
  }
}
BENCHMARK(BM_CraigBamptonBlocks)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_AssemblyBlocks(benchmark::State& state) {
  const auto& b = blocks();
  for (auto _ : state) {
    auto km = fem::assemble(b.mesh, b.materials);
    benchmark::DoNotOptimize(km.K.valuePtr());
  }
}
BENCHMARK(BM_AssemblyBlocks)->Unit(benchmark::kMillisecond)->UseRealTime();

// The stiffness made regular by a small mass shift (free-free K is singular):
// K + 1e-6 (tr K / tr M) M, the pattern of K.
void BM_FactorisationBlocks(benchmark::State& state) {
  const auto& b = blocks();
  const double shift = 1e-6 * b.km.K.diagonal().sum() / b.km.M.diagonal().sum();
  const Eigen::SparseMatrix<double> A = b.km.K + shift * b.km.M;
  for (auto _ : state) {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
    if (ldlt.info() != Eigen::Success) state.SkipWithError("factorisation failed");
    benchmark::DoNotOptimize(ldlt.vectorD().data());
  }
}
BENCHMARK(BM_FactorisationBlocks)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  asperity::bench::RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  auto get = [&](const char* name) { return reporter.seconds_of(name); };
  const double cb = get("BM_CraigBamptonBlocks");
  const double assembly = get("BM_AssemblyBlocks");
  const double factor = get("BM_FactorisationBlocks");
  std::printf("\nRatios (same run, wall time, medians of %lld repetition(s)):\n",
              static_cast<long long>(reporter.repetitions()));
  if (cb > 0 && factor > 0)
    std::printf("  Craig-Bampton / one factorisation of K = %6.2f\n", cb / factor);
  if (cb > 0 && assembly > 0)
    std::printf("  Craig-Bampton / assembly of K and M    = %6.2f\n", cb / assembly);
  if (cb > 0) {
    std::printf(
        "  phases of the last reduction (%ld reduced DOFs, nnz(L + D) %ld, %ld eigensolver "
        "operations):\n",
        static_cast<long>(g_last.K.rows()), static_cast<long>(g_last.factor_nonzeros),
        static_cast<long>(g_last.eigensolver_operations));
    for (const auto& p : g_last.phases)
      std::printf("    %-36s %8.3f s\n", p.name.c_str(), p.seconds);
  }
  benchmark::Shutdown();
  return 0;
}
