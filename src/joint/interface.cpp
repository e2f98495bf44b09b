// The interface pressure field and its patches (see interface.hpp).
#include "asperity/joint/interface.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "asperity/core/error.hpp"

namespace asperity::joint {

namespace {

// Midpoints per cell side for the pressure and area integrals.
constexpr int kSub = 16;

std::vector<double> distinct(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

double mm(double x) {
  return x * 1e3;
}

}  // namespace

bool PressureMap::is_grid() const {
  const auto xs = distinct(x), ys = distinct(y);
  if (xs.size() < 2 || ys.size() < 2 || xs.size() * ys.size() != p.size()) return false;
  std::vector<std::pair<double, double>> pts;
  for (std::size_t i = 0; i < x.size(); ++i) pts.emplace_back(x[i], y[i]);
  std::sort(pts.begin(), pts.end());
  return std::adjacent_find(pts.begin(), pts.end()) == pts.end();
}

void PressureMap::build_index() {
  gx_.clear();
  gy_.clear();
  gp_.clear();
  if (!is_grid()) return;
  gx_ = distinct(x);
  gy_ = distinct(y);
  gp_.assign(gx_.size() * gy_.size(), 0.0);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const auto i =
        static_cast<std::size_t>(std::lower_bound(gx_.begin(), gx_.end(), x[k]) - gx_.begin());
    const auto j =
        static_cast<std::size_t>(std::lower_bound(gy_.begin(), gy_.end(), y[k]) - gy_.begin());
    gp_[i * gy_.size() + j] = p[k];
  }
}

double PressureMap::at(double px, double py) const {
  const auto cell = [](const std::vector<double>& v, double t) {
    const auto it = std::upper_bound(v.begin(), v.end(), t);
    return static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(
        it - v.begin() - 1, 0, static_cast<std::ptrdiff_t>(v.size()) - 2));
  };
  if (!gp_.empty()) {
    const std::size_t i = cell(gx_, px), j = cell(gy_, py), ny = gy_.size();
    const double u = std::clamp((px - gx_[i]) / (gx_[i + 1] - gx_[i]), 0.0, 1.0);
    const double w = std::clamp((py - gy_[j]) / (gy_[j + 1] - gy_[j]), 0.0, 1.0);
    return (1 - u) * (1 - w) * gp_[i * ny + j] + u * (1 - w) * gp_[(i + 1) * ny + j] +
           (1 - u) * w * gp_[i * ny + j + 1] + u * w * gp_[(i + 1) * ny + j + 1];
  }
  if (is_grid()) {  // not indexed: index a copy (slow, correct)
    PressureMap indexed = *this;
    indexed.build_index();
    return indexed.at(px, py);
  }
  std::size_t best = 0;
  double d2 = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double d = (x[k] - px) * (x[k] - px) + (y[k] - py) * (y[k] - py);
    if (d < d2) {
      d2 = d;
      best = k;
    }
  }
  return p[best];
}

double BoltedPressure::footprint_radius() const {
  const double alpha = cone_half_angle_deg * std::numbers::pi / 180.0;
  return 0.5 * head_diameter + std::min(thickness[0], thickness[1]) * std::tan(alpha);
}

void InterfaceSpec::validate(double area) const {
  const std::string w = origin.empty() ? std::string("interface") : origin;
  if (patches[0] < 1 || patches[1] < 1 || patches[0] > 1000 || patches[1] > 1000) {
    throw InvalidInput(fmt::format("{}.patches = [{}, {}]: each count must be in [1, 1000]", w,
                                   patches[0], patches[1]));
  }
  if (pressure != PressureKind::uniform && !outline) {
    throw InvalidInput(fmt::format(
        "{}: a {} pressure needs the outline: size = [\"17 mm\", \"10 mm\"] (Lx along the "
        "fretting direction, Ly across)",
        w, pressure == PressureKind::map ? "map" : "bolted"));
  }
  if (outline) {
    const double Lx = (*outline)[0], Ly = (*outline)[1];
    if (!(Lx > 0.0) || !(Ly > 0.0) || !std::isfinite(Lx * Ly)) {
      throw InvalidInput(
          fmt::format("{}.size = [{} mm, {} mm]: both must be > 0", w, mm(Lx), mm(Ly)));
    }
    if (std::abs(Lx * Ly - area) > 5e-3 * area) {
      throw InvalidInput(fmt::format(
          "{}.size = [{:.6g} mm, {:.6g} mm] spans {:.6g} mm^2, but joint.area = {:.6g} mm^2: "
          "the outline must be the nominal area (to 0.5 %)",
          w, mm(Lx), mm(Ly), Lx * Ly * 1e6, area * 1e6));
    }
  }
  if (pressure == PressureKind::map) {
    if (map.p.empty()) throw InvalidInput(fmt::format("{}.map: the map has no points", w));
    for (std::size_t k = 0; k < map.p.size(); ++k) {
      if (!(map.p[k] >= 0.0) || !std::isfinite(map.p[k])) {
        throw InvalidInput(fmt::format(
            "{}: data row {}: p = {:.6g} Pa at (x, y) = ({:.6g}, {:.6g}) mm: a contact pressure "
            "must be >= 0 (a map with tension is not a contact pressure)",
            map.file, k + 1, map.p[k], mm(map.x[k]), mm(map.y[k])));
      }
    }
    const double Lx = (*outline)[0], Ly = (*outline)[1];
    if (map.is_grid()) {
      const auto [x0, x1] = std::minmax_element(map.x.begin(), map.x.end());
      const auto [y0, y1] = std::minmax_element(map.y.begin(), map.y.end());
      const double tol = 1e-9 * std::max(Lx, Ly);
      if (*x0 > tol || *x1 < Lx - tol || *y0 > tol || *y1 < Ly - tol) {
        throw InvalidInput(fmt::format(
            "{}: the map spans x in [{:.6g}, {:.6g}] mm, y in [{:.6g}, {:.6g}] mm and does not "
            "cover the interface [0, {:.6g}] x [0, {:.6g}] mm (interface.size)",
            map.file, mm(*x0), mm(*x1), mm(*y0), mm(*y1), mm(Lx), mm(Ly)));
      }
    } else {
      const double hx = Lx / patches[0], hy = Ly / patches[1];
      for (int i = 0; i < patches[0]; ++i) {
        for (int j = 0; j < patches[1]; ++j) {
          bool any = false;
          for (std::size_t k = 0; k < map.x.size() && !any; ++k) {
            any = map.x[k] >= i * hx && map.x[k] <= (i + 1) * hx && map.y[k] >= j * hy &&
                  map.y[k] <= (j + 1) * hy;
          }
          if (!any) {
            throw InvalidInput(fmt::format(
                "{}: the map (scattered points, not a full grid) does not cover the interface: "
                "no point in patch [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] mm; give a denser map, "
                "a grid, or fewer patches",
                map.file, mm(i * hx), mm((i + 1) * hx), mm(j * hy), mm((j + 1) * hy)));
          }
        }
      }
    }
  }
  if (pressure == PressureKind::bolted) {
    const auto& b = bolts;
    if (b.positions.empty())
      throw InvalidInput(fmt::format("{}.bolts.positions: give at least one bolt", w));
    if (!(b.head_diameter > 0.0) || !(b.hole_diameter > 0.0) ||
        !(b.hole_diameter < b.head_diameter)) {
      throw InvalidInput(fmt::format(
          "{}.bolts: head_diameter = {:.6g} mm and hole_diameter = {:.6g} mm must be > 0 with "
          "the hole smaller than the head",
          w, mm(b.head_diameter), mm(b.hole_diameter)));
    }
    for (int h = 0; h < 2; ++h) {
      if (!(b.thickness[h] > 0.0) || !std::isfinite(b.thickness[h])) {
        throw InvalidInput(fmt::format("{}.bolts.thickness[{}] = {:.6g} mm must be > 0", w, h + 1,
                                       mm(b.thickness[h])));
      }
    }
    if (!(b.cone_half_angle_deg > 0.0 && b.cone_half_angle_deg < 90.0)) {
      throw InvalidInput(fmt::format("{}.bolts.cone_half_angle = {} deg must be in (0, 90)", w,
                                     b.cone_half_angle_deg));
    }
    const double Lx = (*outline)[0], Ly = (*outline)[1], rh = 0.5 * b.hole_diameter;
    for (std::size_t k = 0; k < b.positions.size(); ++k) {
      const auto [x, y] = b.positions[k];
      if (!(x - rh >= 0.0 && x + rh <= Lx && y - rh >= 0.0 && y + rh <= Ly)) {
        throw InvalidInput(fmt::format(
            "{}.bolts.positions[{}] = ({:.6g}, {:.6g}) mm: the bolt's hole (diameter {:.6g} mm) "
            "must lie inside the outline [0, {:.6g}] x [0, {:.6g}] mm",
            w, k + 1, mm(x), mm(y), mm(b.hole_diameter), mm(Lx), mm(Ly)));
      }
      for (std::size_t l = 0; l < k; ++l) {
        if (std::hypot(x - b.positions[l][0], y - b.positions[l][1]) < b.hole_diameter) {
          throw InvalidInput(
              fmt::format("{}.bolts.positions[{}] and [{}]: the holes overlap", w, l + 1, k + 1));
        }
      }
    }
  }
}

namespace {

struct Sample {
  double x, y, dA;
};

// The midpoints of cell (i, j) inside the interface (outside the holes).
std::vector<Sample> cell_samples(const InterfaceSpec& s, int i, int j) {
  const double Lx = (*s.outline)[0], Ly = (*s.outline)[1];
  const double hx = Lx / s.patches[0], hy = Ly / s.patches[1];
  const double dA = hx * hy / (kSub * kSub);
  const double rh = 0.5 * s.bolts.hole_diameter;
  std::vector<Sample> out;
  for (int a = 0; a < kSub; ++a) {
    for (int c = 0; c < kSub; ++c) {
      const double x = (i + (a + 0.5) / kSub) * hx, y = (j + (c + 0.5) / kSub) * hy;
      bool in_hole = false;
      if (s.pressure == PressureKind::bolted) {
        for (const auto& b : s.bolts.positions) in_hole |= std::hypot(x - b[0], y - b[1]) < rh;
      }
      if (!in_hole) out.push_back({x, y, dA});
    }
  }
  return out;
}

struct Cell {
  std::vector<Sample> samples;
  double area = 0.0;
  double raw_force = 0.0;
};

// Raw (unnormalized) pressure per bolt: the indicator of its annulus.
bool in_cone(const BoltedPressure& b, std::size_t k, double x, double y) {
  const double r = std::hypot(x - b.positions[k][0], y - b.positions[k][1]);
  return r >= 0.5 * b.hole_diameter && r <= b.footprint_radius();
}

// Cells with their samples and the integral of the unnormalized pressure field; `scale`
// turns it into Pa.
std::vector<Cell> cells_with_force(const InterfaceSpec& s, double preload, double& scale) {
  std::vector<Cell> cells;
  for (int i = 0; i < s.patches[0]; ++i) {
    for (int j = 0; j < s.patches[1]; ++j) {
      Cell c;
      c.samples = cell_samples(s, i, j);
      for (const auto& p : c.samples) c.area += p.dA;
      cells.push_back(std::move(c));
    }
  }
  if (s.pressure == PressureKind::bolted) {
    // Each bolt's force, preload/count, over the part of its annulus inside the outline.
    const auto& b = s.bolts;
    std::vector<double> footprint(b.positions.size(), 0.0);
    for (const auto& c : cells)
      for (const auto& p : c.samples)
        for (std::size_t k = 0; k < footprint.size(); ++k)
          if (in_cone(b, k, p.x, p.y)) footprint[k] += p.dA;
    const double F = preload / static_cast<double>(b.positions.size());
    for (auto& c : cells)
      for (const auto& p : c.samples)
        for (std::size_t k = 0; k < footprint.size(); ++k)
          if (in_cone(b, k, p.x, p.y)) c.raw_force += F / footprint[k] * p.dA;
    scale = 1.0;
    return cells;
  }
  double total = 0.0;
  for (auto& c : cells) {
    for (const auto& p : c.samples) {
      c.raw_force += (s.pressure == PressureKind::map ? s.map.at(p.x, p.y) : 1.0) * p.dA;
    }
    total += c.raw_force;
  }
  if (s.pressure == PressureKind::map && !s.map.scale_to_preload) {
    scale = 1.0;
  } else {
    if (!(total > 0.0)) {
      throw InvalidInput(
          fmt::format("{}: the pressure map is zero over the whole interface", s.map.file));
    }
    scale = preload / total;
  }
  return cells;
}

}  // namespace

double halves_compliance(const std::array<double, 2>& E, const HalvesGeometry& g) {
  double C = 0.0;
  for (std::size_t i = 0; i < 2; ++i) {
    for (const auto& [name, v] : {std::pair{"E", E[i]}, std::pair{"length", g.length[i]},
                                  std::pair{"thickness", g.thickness[i]}}) {
      if (!(v > 0.0) || !std::isfinite(v)) {
        throw InvalidInput(
            fmt::format("halves: {} of half {} = {:.6g} (SI) must be > 0", name, i + 1, v));
      }
    }
    if (!(g.width > 0.0) || !std::isfinite(g.width)) {
      throw InvalidInput(fmt::format("halves: width = {:.6g} m must be > 0", g.width));
    }
    C += g.length[i] / (E[i] * g.width * g.thickness[i]);  // a bar: L/(E A)
  }
  return C;
}

double map_total_force(const InterfaceSpec& spec, double area) {
  spec.validate(area);
  double scale = 1.0, total = 0.0;
  for (const auto& c : cells_with_force(spec, 1.0, scale)) total += c.raw_force;
  return total;
}

std::vector<InterfacePatch> interface_patches(const InterfaceSpec& spec, double area,
                                              double preload, double min_patch_area) {
  spec.validate(area);
  if (!(preload > 0.0) || !std::isfinite(preload)) {
    throw InvalidInput(fmt::format("preload = {} N must be > 0", preload));
  }
  const int nx = spec.patches[0], ny = spec.patches[1];
  const std::string w = spec.origin.empty() ? std::string("interface") : spec.origin;
  const auto too_small = [&](double a) {
    return InvalidInput(fmt::format(
        "{}.patches = [{}, {}]: a patch of {:.4g} mm^2 holds fewer than {} asperities (eta "
        "A_patch), too few for the statistics of the rough flat: use fewer patches",
        w, nx, ny, a * 1e6, kMinAsperitiesPerPatch));
  };
  std::vector<InterfacePatch> out;
  if (spec.pressure == PressureKind::uniform) {
    // Equal shares of A0 and of P (the outline, if given, only places the cells).
    const double Lx = spec.outline ? (*spec.outline)[0] : static_cast<double>(nx);
    const double Ly = spec.outline ? (*spec.outline)[1] : static_cast<double>(ny);
    const double n = static_cast<double>(nx) * static_cast<double>(ny);
    if (area / n < min_patch_area) throw too_small(area / n);
    for (int i = 0; i < nx; ++i) {
      for (int j = 0; j < ny; ++j) {
        out.push_back({i * Lx / nx, j * Ly / ny, (i + 1) * Lx / nx, (j + 1) * Ly / ny, area / n,
                       preload / n});
      }
    }
    return out;
  }
  double scale = 1.0;
  auto cells = cells_with_force(spec, preload, scale);
  const double Lx = (*spec.outline)[0], Ly = (*spec.outline)[1];
  const double full = Lx / nx * Ly / ny;
  const auto at = [&](int i, int j) -> Cell& {
    return cells[static_cast<std::size_t>(i * ny + j)];
  };
  // A cell cut by a hole below the minimum joins its largest neighbour (4-neighbours).
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      Cell& c = at(i, j);
      if (c.area <= 0.0 || c.area >= min_patch_area) continue;
      if (c.area > full * (1.0 - 1e-9)) throw too_small(c.area);
      Cell* best = nullptr;
      for (const auto& [di, dj] : {std::pair{-1, 0}, {1, 0}, {0, -1}, {0, 1}}) {
        if (i + di < 0 || i + di >= nx || j + dj < 0 || j + dj >= ny) continue;
        Cell& n = at(i + di, j + dj);
        if (!best || n.area > best->area) best = &n;
      }
      if (!best || best->area + c.area < min_patch_area) throw too_small(c.area);
      best->area += c.area;
      best->raw_force += c.raw_force;
      c.area = 0.0;
      c.raw_force = 0.0;
    }
  }
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      const auto& c = at(i, j);
      if (c.area <= 0.0) continue;  // inside a hole, or joined to a neighbour
      out.push_back({i * Lx / nx, j * Ly / ny, (i + 1) * Lx / nx, (j + 1) * Ly / ny, c.area,
                     c.raw_force * scale});
    }
  }
  return out;
}

}  // namespace asperity::joint
