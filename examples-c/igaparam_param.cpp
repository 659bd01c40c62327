// igaparam_param: the optimized T-mesh parameterization of a planar domain or a solid.
//
//   igaparam_param INPUT OUT_PREFIX [--tol EPS] [--max-level L] [--threads N]
//                  [--boundary-offset X] [--adapt] [--target-quality Q] [--rounds R]
//                  [--no-spline] [--scale SX,SY,SZ] [--smoothing-power P]
//
// INPUT is a G+Smo XML B-rep (four curves, or six surfaces), a coastline .txt, or a folder of six
// surface files xmin, xmax, ymin, ymax, zmin, zmax (.obj, .off, .stl or .ply, read by OpenMesh).
// The default tolerance is 1e-5 for a planar domain, 1e-3 for a solid. Builds the optimized
// T-mesh, fits its cubic THB-spline map and certifies it (with --adapt, the adaptive loop
// refines the T-mesh where the map's mean ratio is under Q or not certified, for at most R
// rounds). --boundary-offset caps the seam relief of the build (how far, relative to the
// bounding box, a boundary vertex may leave the boundary; 0 keeps them all on it). --scale
// multiplies the coordinates of a solid (faces or B-rep) per axis, for data whose axes have
// different units (Floater's parameterization of each face, and q_S, depend on them).
// --smoothing-power sets the power of the distortions the spline smoothing minimises (0, the
// default, chooses: 4 for a planar map, 1 for a solid). Prints the spline's sampled and
// certified smallest mean ratio and how far its boundary strays from the input. Writes
// OUT_PREFIX_tmesh.vtu with VTK (physical T-mesh: one quad or hexahedron per cell through its
// corners, point data `parametric`, cell data `quality` and `level`), OUT_PREFIX_spline.vtu
// (the spline map sampled per element, point data `quality` = q_S and `det`) and OUT_PREFIX.xml
// (the map as G+Smo XML), prints a summary and, as its last line, one JSON object. Exit codes:
// 0 success, 1 error, 2 usage.

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "face_files.h"
#include "igaparam.h"

namespace fs = std::filesystem;

namespace {

// The thread's last error message of the library.
std::string last_error() {
  char buf[1024];
  igaparam_last_error_message(buf, sizeof buf);
  return buf;
}

void check(igaparam_status s, const char* what) {
  if (s != IGAPARAM_STATUS_OK) throw std::runtime_error(std::string(what) + ": " + last_error());
}

// Owns a spline handle.
struct Spline {
  igaparam_spline* s = nullptr;
  Spline() = default;
  Spline(const Spline&) = delete;
  Spline& operator=(const Spline&) = delete;
  ~Spline() { igaparam_spline_free(s); }
};

// Owns a domain handle.
struct Domain {
  igaparam_domain* d = nullptr;
  Domain() = default;
  Domain(const Domain&) = delete;
  Domain& operator=(const Domain&) = delete;
  ~Domain() { igaparam_domain_free(d); }
};

// Opens INPUT; the coordinates of a solid (triangulated faces or a .xml B-rep) are multiplied by
// `scale` per axis (NULL: kept), which planar inputs refuse.
void open_domain(const std::string& input, Domain& domain, const std::array<double, 3>* scale) {
  fs::path path(input);
  if (fs::is_directory(path)) {
    const std::vector<face_files::Face> faces = face_files::read_faces(path, scale);
    face_files::warn_if_anisotropic(faces);
    check(face_files::new_solid(faces, &domain.d), input.c_str());
    return;
  }
  if (!fs::exists(path)) throw std::runtime_error(input + ": no such file or folder");
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  if (scale) {
    if (ext != ".xml") throw std::runtime_error(input + ": --scale applies to solids (faces or .xml) only");
    check(igaparam_domain_new_solid_from_file_scaled(input.c_str(), scale->data(), &domain.d), input.c_str());
    return;
  }
  // A .xml B-rep is planar (four curves) or solid (six surfaces): try planar first.
  igaparam_status s = igaparam_domain_new_from_file(input.c_str(), &domain.d);
  if (s == IGAPARAM_STATUS_OK) return;
  std::string planar_error = last_error();
  if (ext == ".xml" && igaparam_domain_new_solid_from_file(input.c_str(), &domain.d) == IGAPARAM_STATUS_OK)
    return;
  throw std::runtime_error(planar_error + (ext == ".xml" ? " (as a solid: " + last_error() + ")" : ""));
}

// Writes the T-mesh with VTK.
void write_vtu(const igaparam_domain* d, size_t dim, const std::string& out) {
  size_t nv = 0, nc = 0;
  check(igaparam_domain_vertex_count(d, &nv), "vertex count");
  check(igaparam_domain_cell_count(d, &nc), "cell count");
  std::vector<double> uvw(dim * nv), x(dim * nv), quality(nc);
  std::vector<uint8_t> levels(nc);
  size_t per_cell = dim == 2 ? 4 : 8;
  std::vector<size_t> corners(per_cell * nc);
  check(igaparam_domain_copy_vertices(d, uvw.data(), x.data(), dim * nv), "vertices");
  check(igaparam_domain_copy_cell_quality(d, quality.data(), nc), "quality");
  check(igaparam_domain_copy_cells(d, levels.data(), nullptr, nc), "cells");
  check(igaparam_domain_copy_cell_corners(d, corners.data(), corners.size()), "corners");

  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> parametric;
  parametric->SetName("parametric");
  parametric->SetNumberOfComponents(3);
  for (size_t v = 0; v < nv; v++) {
    double p[3] = {0, 0, 0}, u[3] = {0, 0, 0};
    for (size_t k = 0; k < dim; k++) {
      p[k] = x[dim * v + k];
      u[k] = uvw[dim * v + k];
    }
    points->InsertNextPoint(p);
    parametric->InsertNextTuple(u);
  }
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->GetPointData()->AddArray(parametric);
  vtkNew<vtkDoubleArray> q, level;
  q->SetName("quality");
  level->SetName("level");
  for (size_t c = 0; c < nc; c++) {
    std::vector<vtkIdType> ids(corners.begin() + c * per_cell, corners.begin() + (c + 1) * per_cell);
    grid->InsertNextCell(dim == 2 ? VTK_QUAD : VTK_HEXAHEDRON, vtkIdType(per_cell), ids.data());
    q->InsertNextValue(quality[c]);
    level->InsertNextValue(levels[c]);
  }
  grid->GetCellData()->AddArray(q);
  grid->GetCellData()->AddArray(level);
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(out.c_str());
  writer->SetInputData(grid);
  if (writer->Write() != 1) throw std::runtime_error(out + ": VTK cannot write it");
}

// A non-negative integer of at most 32 bits (std::stoul alone takes "-1" and wraps it);
// throws a std::logic_error otherwise.
unsigned parse_count(const std::string& v, size_t& used) {
  if (v.empty() || v[0] < '0' || v[0] > '9') throw std::invalid_argument(v);
  unsigned long x = std::stoul(v, &used);
  if (x > 0xffffffffUL) throw std::out_of_range(v);
  return unsigned(x);
}

int usage(const char* argv0) {
  std::fprintf(stderr,
               "usage: %s INPUT OUT_PREFIX [--tol EPS] [--max-level L] [--threads N]\n"
               "         [--boundary-offset X] [--adapt] [--target-quality Q] [--rounds R]\n"
               "         [--no-spline] [--scale SX,SY,SZ] [--smoothing-power P]\n"
               "  INPUT: G+Smo XML B-rep, coastline .txt, or a folder of six faces\n"
               "  --tol EPS: boundary tolerance (default 1e-5 for a planar domain, 1e-3 for a solid)\n"
               "         xmin xmax ymin ymax zmin zmax (.obj/.off/.stl/.ply)\n"
               "  --boundary-offset X: seam relief cap of the build, relative to the bounding box\n"
               "         (X >= 0, default 1e-2; 0 keeps every boundary vertex on the boundary)\n"
               "  --scale SX,SY,SZ: multiply the coordinates of a solid (faces or .xml) per axis,\n"
               "         to give every axis the same unit (e.g. degrees to km)\n"
               "  --smoothing-power P: power of the distortions the spline smoothing minimises\n"
               "         (0 = automatic, the default: 4 planar, 1 solid; else 1 to 16; not with --adapt)\n",
               argv0);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) return usage(argv[0]);
  std::string input = argv[1], prefix = argv[2];
  igaparam_domain_options options = igaparam_domain_options_default();
  igaparam_adapt_options adapt = igaparam_adapt_options_default();
  igaparam_fit_options fit_options = igaparam_fit_options_default();
  bool adaptive = false, spline_wanted = true;
  std::optional<std::array<double, 3>> scale;
  bool tolerance_given = false;
  try {
    for (int i = 3; i < argc; i++) {
      std::string a = argv[i];
      if (a == "--adapt" || a == "--no-spline") {
        (a == "--adapt" ? adaptive : spline_wanted) = a == "--adapt";
        continue;
      }
      if (i + 1 >= argc) return usage(argv[0]);
      std::string v = argv[++i];
      size_t used = 0;
      if (a == "--tol") {
        options.tolerance = std::stod(v, &used);
        tolerance_given = true;
      } else if (a == "--max-level") {
        options.max_level = parse_count(v, used);
        options.min_level = std::min(options.min_level, options.max_level);
      } else if (a == "--threads") {
        options.threads = parse_count(v, used);
        adapt.threads = options.threads;
        fit_options.threads = options.threads;
      } else if (a == "--target-quality") {
        adapt.target_quality = std::stod(v, &used);
      } else if (a == "--rounds") {
        adapt.max_rounds = parse_count(v, used);
      } else if (a == "--boundary-offset") {
        options.boundary_offset = std::stod(v, &used);
      } else if (a == "--smoothing-power") {
        fit_options.smoothing_power = std::stod(v, &used);
      } else if (a == "--scale") {
        scale = face_files::parse_scale(v);
        used = v.size();
      } else {
        return usage(argv[0]);
      }
      if (used != v.size()) return usage(argv[0]);
    }
  } catch (const std::logic_error&) {
    return usage(argv[0]);
  }
  try {
    Domain domain;
    open_domain(input, domain, scale ? &*scale : nullptr);
    size_t dim = 0;
    check(igaparam_domain_dimension(domain.d, &dim), "dimension");
    if (dim == 3 && !tolerance_given) options.tolerance = igaparam_domain_options_default_solid().tolerance;
    igaparam_domain_report r;
    check(igaparam_domain_build(domain.d, &options, &r), "build");
    std::printf("%s: %zuD T-mesh, %zu cells, %zu vertices, max level %u\n", input.c_str(), dim,
                r.cells, r.vertices, r.max_level);
    std::printf("boundary error %.3e (tolerance %.1e), boundary offset %.3e (cap %.1e)\n", r.boundary_error,
                options.tolerance, r.boundary_offset, options.boundary_offset);
    std::printf("invalid cells %zu after placement, %zu after optimization\n", r.invalid_after_placement,
                r.invalid_cells);
    std::printf("quality min %.4f mean %.4f, %u sweeps%s, %.3f s\n", r.min_quality, r.mean_quality,
                r.sweeps, r.sweep_budget_exhausted ? " (the sweep budget max_total_sweeps ran out)" : "",
                r.seconds);
    std::string spline_json;
    if (spline_wanted) {
      Spline spline;
      igaparam_fit_report fit{};
      igaparam_adapt_report ar{};
      if (adaptive) {
        check(igaparam_domain_fit_adaptive(domain.d, &adapt, &spline.s, &ar), "adaptive fit");
        check(igaparam_domain_cell_count(domain.d, &r.cells), "cell count");
        check(igaparam_domain_vertex_count(domain.d, &r.vertices), "vertex count");
        // The T-mesh figures after the refinements (an invalid cell has quality 0).
        std::vector<double> q(r.cells);
        check(igaparam_domain_copy_cell_quality(domain.d, q.data(), q.size()), "quality");
        r.invalid_cells = size_t(std::count(q.begin(), q.end(), 0.0));
        r.min_quality = *std::min_element(q.begin(), q.end());
        r.mean_quality = 0;
        for (double x : q) r.mean_quality += x / double(q.size());
        std::printf("adaptation: %u rounds, %zu cells refined, now %zu cells; target %s\n", ar.rounds,
                    ar.refined_cells, r.cells, ar.reached ? "reached" : "not reached");
        // The untangling of the last fit, the map returned.
        fit.untangled = ar.untangled;
        fit.boundary_offset = ar.boundary_offset;
        fit.boundary_distance = ar.boundary_distance;
      } else {
        check(igaparam_spline_fit_domain_with(domain.d, &fit_options, &spline.s, &fit), "spline fit");
        if (fit.untangled > 0)
          std::printf("untangling: %zu control points moved, boundary ones at most %.3g of the box\n",
                      fit.untangled, fit.boundary_offset);
      }
      size_t basis = 0, elements = 0;
      check(igaparam_spline_basis_count(spline.s, &basis), "basis count");
      check(igaparam_spline_element_count(spline.s, &elements), "element count");
      igaparam_validity_report v{};
      check(igaparam_spline_check_validity(spline.s, nullptr, &v, nullptr, nullptr, 0), "validity");
      igaparam_quality_bound_report bound{};
      check(igaparam_spline_quality_bound(spline.s, nullptr, &bound), "quality bound");
      std::printf("spline quality: certified min q_S >= %.4f (sampled %.4f); boundary within %.3e of the "
                  "input (relative to the box)\n",
                  bound.lower_bound, bound.sampled_min, fit.boundary_distance);
      const std::string spline_vtu = prefix + "_spline.vtu", xml = prefix + ".xml";
      check(igaparam_spline_write_vtu(spline.s, spline_vtu.c_str(), dim == 2 ? 4 : 2), spline_vtu.c_str());
      check(igaparam_spline_write_gismo(spline.s, xml.c_str()), xml.c_str());
      std::printf("spline: %zu functions on %zu elements, q_S min %.4f mean %.4f, det J %s (bound %.3e); "
                  "wrote %s, %s\n",
                  basis, elements, v.min_quality, v.mean_quality,
                  v.certified_positive ? "certified positive" : "not certified", v.det_lower_bound,
                  spline_vtu.c_str(), xml.c_str());
      char buf[768];
      std::snprintf(buf, sizeof buf,
                    ",\"basis\":%zu,\"elements\":%zu,\"min_q_spline\":%.6f,\"mean_q_spline\":%.6f,"
                    "\"certified_positive\":%s,\"uncertified\":%zu,\"adapt_rounds\":%u,\"untangled\":%zu,"
                    "\"spline_boundary_offset\":%.6e,\"spline_boundary_distance\":%.6e,"
                    "\"min_q_spline_bound\":%.6f,\"fit\":\"%s\"",
                    basis, elements, v.min_quality, v.mean_quality,
                    v.certified_positive ? "true" : "false", v.uncertified, ar.rounds, fit.untangled,
                    fit.boundary_offset, fit.boundary_distance, bound.lower_bound,
                    adaptive                  ? "adaptive"
                    : fit.quasi_interpolation ? "quasi_interpolation"
                    : fit.least_squares       ? "least_squares"
                                              : "interpolation");
      spline_json = buf;
    }
    std::string out = prefix + "_tmesh.vtu";
    write_vtu(domain.d, dim, out);
    std::printf("wrote %s\n", out.c_str());
    std::printf(
        "{\"dim\":%zu,\"cells\":%zu,\"nodes\":%zu,\"max_level\":%u,\"boundary_error\":%.6e,"
        "\"boundary_offset\":%.6e,\"invalid_after_placement\":%zu,\"invalid_cells\":%zu,\"min_quality\":%.6f,"
        "\"mean_quality\":%.6f,\"sweeps\":%u,\"sweep_budget_exhausted\":%s,\"threads\":%u,"
        "\"seconds\":%.4f%s}\n",
        dim, r.cells, r.vertices, r.max_level, r.boundary_error, r.boundary_offset, r.invalid_after_placement,
        r.invalid_cells, r.min_quality, r.mean_quality, r.sweeps, r.sweep_budget_exhausted ? "true" : "false",
        options.threads, r.seconds,
        spline_json.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "igaparam_param: %s\n", e.what());
    return 1;
  }
}
