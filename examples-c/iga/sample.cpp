// sample.cpp: sampled fields and their .vtu output.

#include "sample.h"

#include <fstream>
#include <stdexcept>

namespace iga {

namespace {

// The corners of sub-cell `cell` of an element sampled by n per direction, as point indices
// relative to the element's first point, in VTK's order.
void sub_cell(int d, int n, int cell, int64_t base, std::vector<int64_t> &out) {
  int a[3] = {0, 0, 0}, rest = cell;
  for (int k = 0; k < d; k++) {
    a[k] = rest % n;
    rest /= n;
  }
  static const int corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int v = 0; v < (d == 2 ? 4 : 8); v++) {
    const int i = a[0] + corners[v][0], j = a[1] + corners[v][1], k = a[2] + corners[v][2];
    out.push_back(base + i + (n + 1) * (j + (n + 1) * k));
  }
}

}  // namespace

SampledGrid sample(const Space &sp, int n, const std::vector<FieldSpec> &fields) {
  const int d = sp.d;
  const Reference ref = Reference::grid(d, n);
  int cells_per_element = 1;
  for (int k = 0; k < d; k++) cells_per_element *= n;
  SampledGrid grid;
  grid.d = d;
  for (const FieldSpec &f : fields) grid.fields.push_back({f.name, f.components, {}});
  ElementValues ev;
  std::vector<double> value(9);
  for (size_t e = 0; e < sp.elements.size(); e++) {
    const Element &el = sp.elements[e];
    element_values(sp, el, ref, ev);
    const int64_t base = static_cast<int64_t>(grid.points.size() / 3);
    for (int q = 0; q < ref.nq; q++) {
      for (int k = 0; k < 3; k++) grid.points.push_back(k < d ? ev.points(k, q) : 0.0);
      for (size_t f = 0; f < fields.size(); f++) {
        fields[f].value(el, ev, q, value.data());
        grid.fields[f].values.insert(grid.fields[f].values.end(), value.begin(), value.begin() + fields[f].components);
      }
    }
    for (int c = 0; c < cells_per_element; c++) {
      sub_cell(d, n, c, base, grid.cells);
      grid.element.push_back(double(e));
      grid.level.push_back(double(el.level));
    }
  }
  return grid;
}

void write_vtu(const SampledGrid &grid, const std::string &path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  const size_t per_cell = grid.d == 2 ? 4 : 8, np = grid.points.size() / 3, nc = grid.cells.size() / per_cell;
  out.precision(12);
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "<UnstructuredGrid><Piece NumberOfPoints=\"" << np << "\" NumberOfCells=\"" << nc << "\">\n<PointData>\n";
  for (const auto &f : grid.fields) {
    out << "<DataArray type=\"Float64\" Name=\"" << f.name << "\" NumberOfComponents=\"" << f.components
        << "\" format=\"ascii\">\n";
    for (size_t i = 0; i < f.values.size(); i++) out << f.values[i] << ((i + 1) % f.components ? " " : "\n");
    out << "</DataArray>\n";
  }
  out << "</PointData>\n<CellData>\n";
  for (const auto *array : {&grid.element, &grid.level}) {
    out << "<DataArray type=\"Float64\" Name=\"" << (array == &grid.element ? "element" : "level")
        << "\" format=\"ascii\">\n";
    for (double v : *array) out << v << "\n";
    out << "</DataArray>\n";
  }
  out << "</CellData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (size_t i = 0; i < np; i++)
    out << grid.points[3 * i] << " " << grid.points[3 * i + 1] << " " << grid.points[3 * i + 2] << "\n";
  out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (size_t i = 0; i < grid.cells.size(); i++) out << grid.cells[i] << ((i + 1) % per_cell == 0 ? "\n" : " ");
  out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (size_t i = 1; i <= nc; i++) out << i * per_cell << "\n";
  out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (size_t i = 0; i < nc; i++) out << (grid.d == 2 ? 9 : 12) << "\n";
  out << "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace iga
