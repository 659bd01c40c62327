// sample.h: fields of an analysis space sampled on a grid of sub-cells per element, and their
// ASCII .vtu output.

#ifndef IGAPARAM_IGA_SAMPLE_H
#define IGAPARAM_IGA_SAMPLE_H

#include "space.h"

namespace iga {

/// A field to sample: `value(el, ev, q, out)` writes its `components` values at point q of
/// the element's sample points.
struct FieldSpec {
  std::string name;
  int components = 1;
  std::function<void(const Element &, const ElementValues &, int, double *)> value;
};

/// The sampled grid: n^d quads or hexahedra per element through (n+1)^d points (points of
/// neighbouring elements are not merged), point fields, and per cell its element and level.
struct SampledGrid {
  struct Field {
    std::string name;
    int components = 1;
    std::vector<double> values;  // components per point
  };
  int d = 2;
  std::vector<double> points;   // 3 per point
  std::vector<int64_t> cells;   // 2^d per cell, VTK quad / hexahedron order
  std::vector<double> element, level;  // per cell
  std::vector<Field> fields;
};

/// Samples the fields on (n+1)^d points per element.
SampledGrid sample(const Space &sp, int n, const std::vector<FieldSpec> &fields);

/// Writes the grid as an ASCII VTK unstructured grid (point data: the fields; cell data:
/// `element`, `level`).
void write_vtu(const SampledGrid &grid, const std::string &path);

}  // namespace iga

#endif  // IGAPARAM_IGA_SAMPLE_H
