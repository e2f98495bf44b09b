// VTK XML unstructured grid, ASCII ("VTK File Formats", VTK User's Guide, XML formats;
// cell types VTK_QUADRATIC_TETRA = 24 and VTK_QUADRATIC_HEXAHEDRON = 25, vtkCellType.h,
// whose node orders are the canonical orders of mesh.hpp).
#include <fmt/format.h>

#include <cmath>
#include <functional>
#include <set>
#include <string>
#include <utility>

#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/fem/mesh_io.hpp"

namespace asperity::fem {
namespace {

std::string xml_escaped(std::string_view s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

void check_fields(const Mesh& mesh, const std::vector<PointField>& fields) {
  std::set<std::string> names;
  for (std::size_t f = 0; f < fields.size(); ++f) {
    const auto& field = fields[f];
    const std::string item = fmt::format("point field {} (\"{}\")", f, core::printable(field.name));
    if (field.name.empty()) throw InvalidInput(fmt::format("{}: the name is empty", item));
    if (field.name.find_first_of("\r\n") != std::string::npos) {
      throw InvalidInput(fmt::format("{}: the name has a line break", item));
    }
    if (!names.insert(field.name).second) {
      throw InvalidInput(fmt::format("{}: another field has the same name", item));
    }
    if (field.values.rows() != 1 && field.values.rows() != 3) {
      throw InvalidInput(
          fmt::format("{}: {} rows (components); 1 or 3 are allowed", item, field.values.rows()));
    }
    if (field.values.cols() != mesh.nodes.cols()) {
      throw InvalidInput(fmt::format("{}: {} columns; one per node ({}) is needed", item,
                                     field.values.cols(), mesh.nodes.cols()));
    }
    for (Eigen::Index j = 0; j < field.values.cols(); ++j) {
      for (Eigen::Index i = 0; i < field.values.rows(); ++i) {
        if (!std::isfinite(field.values(i, j))) {
          throw InvalidInput(fmt::format("{}: the value at node {}, component {} is {}", item, j, i,
                                         core::format_value(field.values(i, j))));
        }
      }
    }
  }
  for (Eigen::Index j = 0; j < mesh.nodes.cols(); ++j) {
    if (!mesh.nodes.col(j).allFinite()) {
      throw InvalidInput(fmt::format("mesh node {} has a non-finite coordinate", j));
    }
  }
  for (const auto& block : mesh.blocks) {
    for (const auto node : block.connectivity) {
      if (node < 0 || node >= mesh.nodes.cols()) {
        throw InvalidInput(fmt::format("mesh element node index {} is out of range [0, {})", node,
                                       mesh.nodes.cols()));
      }
    }
  }
}

}  // namespace

void write_vtu(const std::string& path, const Mesh& mesh, const std::vector<PointField>& fields) {
  check_fields(mesh, fields);
  std::size_t cells = 0;
  for (const auto& block : mesh.blocks) cells += block.size();
  core::OutputSet out;
  out.add_streamed(path, [&](const std::function<void(std::string_view)>& sink) {
    std::string s;
    const auto flush = [&] {
      if (s.size() > (1 << 16)) sink(std::exchange(s, {}));
    };
    s += "<?xml version=\"1.0\"?>\n";
    s += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n";
    s += "  <UnstructuredGrid>\n";
    s += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", mesh.nodes.cols(),
                     cells);
    s += "      <PointData>\n";
    for (const auto& field : fields) {
      s += fmt::format(
          "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" "
          "format=\"ascii\">\n",
          xml_escaped(field.name), field.values.rows());
      for (Eigen::Index j = 0; j < field.values.cols(); ++j) {
        for (Eigen::Index i = 0; i < field.values.rows(); ++i) {
          if (i > 0) s += ' ';
          s += fmt::format("{}", field.values(i, j));
        }
        s += '\n';
        flush();
      }
      s += "        </DataArray>\n";
    }
    s += "      </PointData>\n";
    s += "      <CellData>\n";
    s += "        <DataArray type=\"Int32\" Name=\"body\" format=\"ascii\">\n";
    for (const auto& block : mesh.blocks) {
      for (const auto b : block.body) {
        s += fmt::format("{}\n", b);
        flush();
      }
    }
    s += "        </DataArray>\n";
    s += "      </CellData>\n";
    s += "      <Points>\n";
    s += "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (Eigen::Index j = 0; j < mesh.nodes.cols(); ++j) {
      s += fmt::format("{} {} {}\n", mesh.nodes(0, j), mesh.nodes(1, j), mesh.nodes(2, j));
      flush();
    }
    s += "        </DataArray>\n";
    s += "      </Points>\n";
    s += "      <Cells>\n";
    s += "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const auto& block : mesh.blocks) {
      for (std::size_t e = 0; e < block.size(); ++e) {
        const auto nodes = block.element(e);
        for (std::size_t k = 0; k < nodes.size(); ++k) {
          if (k > 0) s += ' ';
          s += fmt::format("{}", nodes[k]);
        }
        s += '\n';
        flush();
      }
    }
    s += "        </DataArray>\n";
    s += "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    std::size_t offset = 0;
    for (const auto& block : mesh.blocks) {
      const auto n = static_cast<std::size_t>(nodes_per_element(block.type));
      for (std::size_t e = 0; e < block.size(); ++e) {
        offset += n;
        s += fmt::format("{}\n", offset);
        flush();
      }
    }
    s += "        </DataArray>\n";
    s += "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (const auto& block : mesh.blocks) {
      const int vtk_type = block.type == ElementType::tet10 ? 24 : 25;
      for (std::size_t e = 0; e < block.size(); ++e) {
        s += fmt::format("{}\n", vtk_type);
        flush();
      }
    }
    s += "        </DataArray>\n";
    s += "      </Cells>\n";
    s += "    </Piece>\n";
    s += "  </UnstructuredGrid>\n";
    s += "</VTKFile>\n";
    sink(s);
  });
  out.commit();
}

}  // namespace asperity::fem
