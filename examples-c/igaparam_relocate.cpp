// igaparam_relocate: relocates the free nodes of a quad/hex mesh stored as a VTK .vtu file.
//
// The input's point arrays say how the boundary moves: `fixed_components` (UInt8 bit mask: bit 0
// keeps x, bit 1 y, bit 2 z) and `moved` (3 doubles, the new positions). For every node with a
// non-zero mask, its fixed coordinates are set to `moved` and its free ones keep their values;
// then the library relocates all free coordinates. The output has the new points, a cell array
// `quality` and a point array `displacement` (new - input position), plus the input's arrays.
//
// The human summary goes to stdout; its last line is one JSON object with the figures.

#include <unistd.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "igaparam.hpp"
#if IGAPARAM_RENDER
#include "render_picture.h"
#endif
#include "vtu_io.h"

namespace {

using vtu_io::capture_vtk_messages;
using vtu_io::read_grid;

constexpr const char* kUsage =
    "usage: igaparam_relocate IN.vtu OUT.vtu [--threads N] [--target initial|master]\n"
    "                         [--laplacian-only] [--max-sweeps N] [--png OUT.png]\n"
    "\n"
    "Relocates the free nodes of a mesh of one cell type among Q4, Q8, Q9, H8, H20, H27\n"
    "(VTK types 9, 23, 28, 12, 25, 29). Point arrays of IN.vtu:\n"
    "  fixed_components  UInt8 mask of the coordinates a node keeps (bit 0 x, 1 y, 2 z)\n"
    "  moved             3 doubles: the new position of the fixed coordinates\n"
    "OUT.vtu gets the new points, a cell array `quality` and a point array `displacement`.\n"
    "\n"
    "options:\n"
    "  --threads N        worker threads (default 0: one per core)\n"
    "  --target T         ideal cell shape: `initial` (input cells, default) or `master`\n"
    "  --laplacian-only   stop after the harmonic placement (no optimization)\n"
    "  --max-sweeps N     largest number of optimization sweeps per step (default 100)\n"
    "  --png OUT.png      also draw the result, cells coloured by quality, to OUT.png (needs an\n"
    "                     X display: run under xvfb-run when there is none)\n"
    "  --help             this text\n"
    "\n"
    "The last line of stdout is a JSON object; exit code 0 on success, 1 on error, 2 on usage error.\n";

/// A command-line mistake: reported with the usage text and exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Arguments {
  std::string input;
  std::string output;
  std::string png;  // empty: no picture
  igaparam_relocate_options options = igaparam::default_options();
};

unsigned parse_count(const std::string& option, const std::string& text) {
  std::size_t end = 0;
  unsigned long value = 0;
  try {
    if (!text.empty() && text[0] != '-') value = std::stoul(text, &end);
  } catch (const std::exception&) {
    end = 0;
  }
  if (end == 0 || end != text.size() || value > 0xffffffffUL) {
    throw UsageError(option + " expects a non-negative integer, not `" + text + "`");
  }
  return static_cast<unsigned>(value);
}

/// Parses the command line; returns nothing for --help.
std::optional<Arguments> parse_arguments(int argc, char** argv) {
  Arguments args;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; i++) {
    const std::string arg = argv[i];
    // The value of an option that takes one.
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(arg + " expects a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      return std::nullopt;
    } else if (arg == "--threads") {
      args.options.threads = parse_count(arg, value());
    } else if (arg == "--max-sweeps") {
      args.options.max_sweeps = parse_count(arg, value());
    } else if (arg == "--png") {
      args.png = value();
    } else if (arg == "--laplacian-only") {
      args.options.optimize = 0;
    } else if (arg == "--target") {
      const std::string t = value();
      if (t == "initial") {
        args.options.target = IGAPARAM_TARGET_INITIAL;
      } else if (t == "master") {
        args.options.target = IGAPARAM_TARGET_MASTER;
      } else {
        throw UsageError("--target expects `initial` or `master`, not `" + t + "`");
      }
    } else if (arg.size() > 1 && arg[0] == '-') {
      throw UsageError("unknown option " + arg);
    } else {
      positional.push_back(arg);
    }
  }
  if (positional.size() != 2) {
    throw UsageError("expected IN.vtu and OUT.vtu, got " + std::to_string(positional.size()) + " file names");
  }
  args.input = positional[0];
  args.output = positional[1];
  return args;
}

struct CellTypeInfo {
  int vtk_type;
  std::size_t nodes;
  const char* name;
};

constexpr CellTypeInfo kCellTypes[] = {
    {IGAPARAM_CELL_QUAD4, 4, "VTK_QUAD"},
    {IGAPARAM_CELL_QUAD8, 8, "VTK_QUADRATIC_QUAD"},
    {IGAPARAM_CELL_QUAD9, 9, "VTK_BIQUADRATIC_QUAD"},
    {IGAPARAM_CELL_HEX8, 8, "VTK_HEXAHEDRON"},
    {IGAPARAM_CELL_HEX20, 20, "VTK_QUADRATIC_HEXAHEDRON"},
    {IGAPARAM_CELL_HEX27, 27, "VTK_TRIQUADRATIC_HEXAHEDRON"},
};

const CellTypeInfo* find_cell_type(int vtk_type) {
  for (const auto& info : kCellTypes) {
    if (info.vtk_type == vtk_type) return &info;
  }
  return nullptr;
}

/// The grid's one cell type; throws if it is unsupported or if cell types are mixed.
const CellTypeInfo& grid_cell_type(vtkUnstructuredGrid* grid) {
  const int first = grid->GetCellType(0);
  const CellTypeInfo* info = find_cell_type(first);
  if (info == nullptr) {
    throw std::runtime_error("cell 0 has VTK type " + std::to_string(first) +
                             "; supported: 9 (Q4), 23 (Q8), 28 (Q9), 12 (H8), 25 (H20), 29 (H27)");
  }
  for (vtkIdType c = 1; c < grid->GetNumberOfCells(); c++) {
    if (grid->GetCellType(c) != first) {
      throw std::runtime_error("cells of several types (cell 0: " + std::to_string(first) + ", cell " +
                               std::to_string(c) + ": " + std::to_string(grid->GetCellType(c)) +
                               "); all cells must have one type");
    }
  }
  return *info;
}

std::vector<double> grid_points(vtkUnstructuredGrid* grid) {
  std::vector<double> xyz(3 * static_cast<std::size_t>(grid->GetNumberOfPoints()));
  for (vtkIdType v = 0; v < grid->GetNumberOfPoints(); v++) grid->GetPoint(v, &xyz[3 * v]);
  return xyz;
}

std::vector<std::int64_t> grid_connectivity(vtkUnstructuredGrid* grid, const CellTypeInfo& type) {
  std::vector<std::int64_t> connectivity;
  connectivity.reserve(type.nodes * grid->GetNumberOfCells());
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); c++) {
    grid->GetCellPoints(c, ids);
    if (static_cast<std::size_t>(ids->GetNumberOfIds()) != type.nodes) {
      throw std::runtime_error("cell " + std::to_string(c) + " has " + std::to_string(ids->GetNumberOfIds()) +
                               " nodes, a " + type.name + " has " + std::to_string(type.nodes));
    }
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); k++) connectivity.push_back(ids->GetId(k));
  }
  return connectivity;
}

/// The point array `name` if present; throws if it has not `components` components.
vtkDataArray* point_array(vtkUnstructuredGrid* grid, const char* name, int components) {
  vtkDataArray* array = grid->GetPointData()->GetArray(name);
  if (array != nullptr && array->GetNumberOfComponents() != components) {
    throw std::runtime_error(std::string("point array `") + name + "` has " +
                             std::to_string(array->GetNumberOfComponents()) + " components, expected " +
                             std::to_string(components));
  }
  return array;
}

/// Applies the point arrays `fixed_components` and `moved` to the mesh.
void apply_constraints(igaparam::Mesh& mesh, vtkUnstructuredGrid* grid, const std::vector<double>& xyz) {
  vtkDataArray* fixed = point_array(grid, "fixed_components", 1);
  vtkDataArray* moved = point_array(grid, "moved", 3);
  if (fixed == nullptr) {
    std::cerr << "igaparam_relocate: warning: no point array `fixed_components`: no node is constrained, "
                 "so the mesh keeps its shape\n";
    return;
  }
  if (moved == nullptr) {
    std::cerr << "igaparam_relocate: warning: no point array `moved`: the constrained nodes keep their positions\n";
  }
  const vtkIdType n = grid->GetNumberOfPoints();
  std::vector<std::uint8_t> mask(n);
  std::vector<std::int64_t> indices;
  std::vector<double> targets;
  for (vtkIdType v = 0; v < n; v++) {
    const double m = fixed->GetTuple1(v);
    if (!(m >= 0 && m <= 255) || m != std::floor(m)) {
      throw std::runtime_error("fixed_components[" + std::to_string(v) + "] = " + std::to_string(m) +
                               " is not a mask in 0..7");
    }
    mask[v] = static_cast<std::uint8_t>(m);
    if (mask[v] == 0 || moved == nullptr) continue;
    const double* to = moved->GetTuple3(v);
    indices.push_back(v);
    for (int d = 0; d < 3; d++) targets.push_back((mask[v] >> d) & 1 ? to[d] : xyz[3 * v + d]);
  }
  mesh.move_nodes(indices, targets);
  mesh.set_fixed(mask);
}

/// Reports optimization sweeps on stderr: every sweep on one line on a terminal, else every 10th.
class ProgressPrinter {
 public:
  ProgressPrinter() : terminal_(isatty(STDERR_FILENO) != 0) {}
  ~ProgressPrinter() {
    if (terminal_ && printed_) std::fputc('\n', stderr);
  }

  bool operator()(igaparam_stage stage, std::size_t done, std::size_t total) {
    if (stage != IGAPARAM_STAGE_OPTIMIZATION || done == 0 || (!terminal_ && done % 10 != 0)) return true;
    std::fprintf(stderr, terminal_ ? "\rsweep %zu" : "sweep %zu", done);
    if (total > 0) std::fprintf(stderr, " of at most %zu", total);
    std::fputs(terminal_ ? "   " : "\n", stderr);
    std::fflush(stderr);
    printed_ = true;
    return true;
  }

 private:
  bool terminal_;
  bool printed_ = false;
};

vtkSmartPointer<vtkDoubleArray> named_array(const char* name, int components, const std::vector<double>& values) {
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / components));
  for (std::size_t i = 0; i < values.size(); i++) array->SetValue(static_cast<vtkIdType>(i), values[i]);
  return array;
}

/// Writes `grid` with its points replaced by `xyz` and the arrays `quality` and `displacement`.
void write_grid(vtkUnstructuredGrid* grid, const std::string& path, const std::vector<double>& original,
                const std::vector<double>& xyz, const std::vector<double>& quality) {
  std::vector<double> displacement(xyz.size());
  for (std::size_t i = 0; i < xyz.size(); i++) displacement[i] = xyz[i] - original[i];
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetData(named_array("Points", 3, xyz));
  grid->SetPoints(points);
  grid->GetCellData()->AddArray(named_array("quality", 1, quality));
  grid->GetPointData()->AddArray(named_array("displacement", 3, displacement));

  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  auto messages = capture_vtk_messages();
  writer->SetFileName(path.c_str());
  writer->SetInputData(grid);
  writer->SetDataModeToBinary();
  const bool written = writer->Write() == 1;
  messages->throw_if_failed("cannot write " + path, !written);
}

/// A JSON number (null for NaN or infinity, which JSON lacks).
std::string json_number(double value) {
  if (!std::isfinite(value)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", value);
  return text;
}

void print_summary(const std::string& input, const CellTypeInfo& type, const igaparam_relocate_options& options,
                   const igaparam_relocate_report& r) {
  const char* target = options.target == IGAPARAM_TARGET_MASTER ? "master" : "initial";
  std::printf("igaparam %s: %s\n", igaparam::version().c_str(), input.c_str());
  std::printf("  cells          %zu (%s)\n", r.cells, type.name);
  std::printf("  nodes          %zu (%zu free)\n", r.nodes, r.free_nodes);
  std::printf("  invalid cells  %zu before, %zu after placement, %zu after\n", r.invalid_before,
              r.invalid_after_placement, r.invalid_after);
  std::printf("  quality        min %.4f, mean %.4f (target %s)\n", r.min_quality, r.mean_quality, target);
  std::printf("  sweeps         %u in %u step%s (%s)%s\n", r.sweeps, r.steps, r.steps == 1 ? "" : "s",
              r.converged ? "converged" : "not converged", options.optimize ? "" : ", placement only");
  std::printf("  time           %.3f s, threads %u%s\n", r.seconds, options.threads,
              options.threads == 0 ? " (one per core)" : "");
  std::printf(
      "{\"cells\":%zu,\"nodes\":%zu,\"free_nodes\":%zu,\"cell_type\":\"%s\",\"invalid_before\":%zu,"
      "\"invalid_after_placement\":%zu,\"invalid_after\":%zu,\"min_quality\":%s,\"mean_quality\":%s,"
      "\"sweeps\":%u,\"steps\":%u,\"converged\":%s,\"seconds\":%s,\"threads\":%u,\"target\":\"%s\",\"optimize\":%s}\n",
      r.cells, r.nodes, r.free_nodes, type.name, r.invalid_before, r.invalid_after_placement, r.invalid_after,
      json_number(r.min_quality).c_str(), json_number(r.mean_quality).c_str(), r.sweeps, r.steps,
      r.converged ? "true" : "false", json_number(r.seconds).c_str(), options.threads, target,
      options.optimize ? "true" : "false");
}

int run(const Arguments& args) {
  vtkSmartPointer<vtkUnstructuredGrid> grid = read_grid(args.input);
  const CellTypeInfo& type = grid_cell_type(grid);
  const std::vector<double> original = grid_points(grid);
  igaparam::Mesh mesh(type.vtk_type, original, grid_connectivity(grid, type));
  apply_constraints(mesh, grid, original);

  igaparam_relocate_report report{};
  {
    ProgressPrinter printer;
    report = mesh.relocate(args.options, std::ref(printer));
  }
  write_grid(grid, args.output, original, mesh.positions(), mesh.cell_quality(args.options.target));
  print_summary(args.input, type, args.options, report);
  if (!args.png.empty()) {
    std::fflush(stdout);
#if IGAPARAM_RENDER
    render_picture::MeshPicture picture;
    picture.title = args.output;
    picture.subtitle = render_picture::array_summary(grid, "quality");
    render_picture::render_mesh_png(grid, picture, args.png);
#else
    throw std::runtime_error("cannot draw " + args.png + ": this build has no VTK rendering modules");
#endif
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);  // VTK errors are reported as ours
  std::optional<Arguments> args;
  try {
    args = parse_arguments(argc, argv);
  } catch (const UsageError& e) {
    std::cerr << "igaparam_relocate: " << e.what() << "\n\n" << kUsage;
    return 2;
  }
  if (!args) {
    std::cout << kUsage;
    return 0;
  }
  try {
    return run(*args);
  } catch (const igaparam::Error& e) {
    std::cerr << "igaparam_relocate: " << e.what() << " (status " << static_cast<int>(e.status()) << ")\n";
  } catch (const std::exception& e) {
    std::cerr << "igaparam_relocate: " << e.what() << "\n";
  }
  return 1;
}
