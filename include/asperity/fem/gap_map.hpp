#pragma once
// An initial (mesoscale) gap over an interface on a regular grid: what a flatness scan of the
// contact faces gives (the Brake-Reuss beam's `mesoscale_xygap`, docs/brb.md).
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "asperity/fem/reduced_model.hpp"

namespace asperity::fem {

struct GapMap {
  double x0 = 0.0, y0 = 0.0;  ///< first grid point [m]
  double dx = 0.0, dy = 0.0;  ///< spacing [m]
  Eigen::Index nx = 0, ny = 0;
  Eigen::MatrixXd gap;  ///< nx x ny [m], NaN where there is no surface (holes)
  std::string source;
};

/// Reads a MATLAB v5 file's `variable` (P x 3: x [m], y [m], gap [m]; NaN gaps allowed) whose
/// points form a full regular grid. InvalidInput names the file: not a grid, a negative or
/// infinite gap, fewer than 2 x 2 points.
[[nodiscard]] GapMap read_gap_map(const std::string& path,
                                  const std::string& variable = "mesoscale_xygap");

/// The gap at each interface element's centroid: the map's (x, y) are taken along the global
/// x and y axes from `origin` [m]. Bilinear between the four grid points around it where all
/// have a gap; where some lie in a hole, the mean of the others; InvalidInput naming the
/// element when the centroid lies outside the map (by more than half a spacing) or all four
/// are holes.
[[nodiscard]] Eigen::VectorXd gap_at_elements(const GapMap& map, const ReducedModel& model,
                                              const Eigen::Vector3d& origin);

}  // namespace asperity::fem
