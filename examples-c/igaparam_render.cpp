// igaparam_render: PNG pictures of the project's .vtu outputs (relocated Q9/H27 meshes, 2D/3D
// T-meshes), and sorted-quality charts comparing meshes. Renders offscreen with VTK; needs an X
// display (run under xvfb-run when there is none).

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkLogger.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "render_convergence.h"
#include "render_picture.h"
#include "vtu_io.h"

namespace {

constexpr const char* kUsage =
    "usage: igaparam_render IN.vtu OUT.png [options]\n"
    "       igaparam_render --sorted-quality IN.vtu... OUT.png [--labels A,B,...] [options]\n"
    "       igaparam_render --convergence SERIES.txt... OUT.png [--labels A,B,...] [--title T] [--size W H]\n"
    "\n"
    "Draws the mesh of IN.vtu (2D: its cells; 3D: its outer surface) coloured by a cell or point\n"
    "array, with a colour bar and the cell edges. With --sorted-quality, draws instead the values\n"
    "of the array over the cells of each file, sorted ascending (one curve per file). With\n"
    "--convergence, draws the H1 and L2 errors against the dofs (log-log) of the series in the\n"
    "last JSON line of each file (igaparam_poisson's output: an adaptive series with the uniform one\n"
    "beside it, or a uniform series), with the optimal H1 slope.\n"
    "\n"
    "options:\n"
    "  --array NAME        cell array (or else point array) to colour by (default `quality`;\n"
    "                      a vector array colours by its magnitude)\n"
    "  --range MIN MAX     colour range (default: the array's range)\n"
    "  --title TEXT        title (default: IN.vtu; `` for none)\n"
    "  --size W H          picture size in pixels (default 1000 750; charts 1000 650)\n"
    "  --no-edges          do not draw the cell edges\n"
    "  --cut AXIS F        3D: keep the cells whose centre lies below the fraction F (0..1) of the\n"
    "                      bounding box along AXIS (x, y or z), to show the inside\n"
    "  --view AZ EL        3D: camera azimuth and elevation in degrees (default 35 25)\n"
    "  --stretch X Y Z     draw the mesh with its axes multiplied by X, Y, Z (> 0; e.g. the\n"
    "                      vertical exaggeration of a terrain); the colours are unchanged\n"
    "  --labels A,B,...    curve labels of --sorted-quality (default: the file names)\n"
    "  --help              this text\n"
    "\n"
    "Exit code 0 on success, 1 on error, 2 on usage error, 77 when no X display can be opened.\n";

constexpr int kNoDisplayExit = 77;

/// A command-line mistake: reported with the usage text and exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Arguments {
  bool sorted_quality = false, convergence = false;
  std::vector<std::string> inputs;
  std::string output;
  std::optional<std::string> title;
  std::vector<std::string> labels;
  int width = 0, height = 0;  // 0: the default size
  render_picture::MeshPicture picture;
};

double parse_number(const std::string& option, const std::string& text) {
  std::size_t end = 0;
  double value = NAN;
  try {
    value = std::stod(text, &end);
  } catch (const std::exception&) {
    end = 0;
  }
  if (end == 0 || end != text.size() || !std::isfinite(value)) {
    throw UsageError(option + " expects a number, not `" + text + "`");
  }
  return value;
}

int parse_size(const std::string& option, const std::string& text) {
  const double value = parse_number(option, text);
  if (value != std::floor(value) || value < 64 || value > 8192) {
    throw UsageError(option + " expects whole pixel counts in 64..8192, not `" + text + "`");
  }
  return static_cast<int>(value);
}

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma - start));
    if (comma == std::string::npos) return parts;
    start = comma + 1;
  }
}

/// Parses the command line; returns nothing for --help.
std::optional<Arguments> parse_arguments(int argc, char** argv) {
  Arguments args;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; i++) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(arg + " expects a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      return std::nullopt;
    } else if (arg == "--sorted-quality") {
      args.sorted_quality = true;
    } else if (arg == "--convergence") {
      args.convergence = true;
    } else if (arg == "--array") {
      args.picture.array = value();
    } else if (arg == "--range") {
      args.picture.range_min = parse_number(arg, value());
      args.picture.range_max = parse_number(arg, value());
      if (!(args.picture.range_max > args.picture.range_min)) throw UsageError("--range expects MIN < MAX");
    } else if (arg == "--title") {
      args.title = value();
    } else if (arg == "--size") {
      args.width = parse_size(arg, value());
      args.height = parse_size(arg, value());
    } else if (arg == "--no-edges") {
      args.picture.edges = false;
    } else if (arg == "--cut") {
      const std::string axis = value();
      if (axis != "x" && axis != "y" && axis != "z") throw UsageError("--cut expects an axis x, y or z, not `" + axis + "`");
      args.picture.cut_axis = axis[0] - 'x';
      args.picture.cut_fraction = parse_number(arg, value());
      if (!(args.picture.cut_fraction > 0 && args.picture.cut_fraction <= 1)) {
        throw UsageError("--cut expects a fraction in (0, 1]");
      }
    } else if (arg == "--view") {
      args.picture.azimuth = parse_number(arg, value());
      args.picture.elevation = parse_number(arg, value());
    } else if (arg == "--stretch") {
      for (double& f : args.picture.stretch) {
        f = parse_number(arg, value());
        if (!(f > 0 && std::isfinite(f))) throw UsageError("--stretch expects three positive factors");
      }
    } else if (arg == "--labels") {
      args.labels = split_commas(value());
    } else if (arg.size() > 1 && arg[0] == '-') {
      throw UsageError("unknown option " + arg);
    } else {
      positional.push_back(arg);
    }
  }
  const bool charts = args.sorted_quality || args.convergence;
  if (args.sorted_quality && args.convergence) throw UsageError("--sorted-quality or --convergence, not both");
  if (positional.size() < 2 || (!charts && positional.size() != 2)) {
    throw UsageError(charts ? "expected IN... OUT.png" : "expected IN.vtu and OUT.png");
  }
  args.output = positional.back();
  positional.pop_back();
  args.inputs = positional;
  if (!args.labels.empty() && args.labels.size() != args.inputs.size()) {
    throw UsageError("--labels gives " + std::to_string(args.labels.size()) + " labels for " +
                     std::to_string(args.inputs.size()) + " files");
  }
  return args;
}

/// The file name of a path, without its directory.
std::string file_name(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

/// The values of the scalar array `name` over the cells of `grid`.
std::vector<double> cell_values(vtkUnstructuredGrid* grid, const std::string& name, const std::string& path) {
  vtkDataArray* array = grid->GetCellData()->GetArray(name.c_str());
  if (array == nullptr || array->GetNumberOfComponents() != 1) {
    throw std::runtime_error(path + " has no scalar cell array `" + name +
                             "`; it has: " + render_picture::array_names(grid));
  }
  std::vector<double> values(static_cast<std::size_t>(array->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); i++) values[static_cast<std::size_t>(i)] = array->GetTuple1(i);
  return values;
}

int run(const Arguments& args) {
  if (args.convergence) {
    std::vector<render_convergence::Curve> curves;
    for (std::size_t i = 0; i < args.inputs.size(); i++) {
      const std::string prefix = args.labels.empty() ? (args.inputs.size() > 1 ? file_name(args.inputs[i]) + ": " : "")
                                                     : args.labels[i] + ": ";
      for (auto& c : render_convergence::convergence_curves(render_convergence::last_json_line(args.inputs[i]), prefix))
        curves.push_back(c);
    }
    render_convergence::render_loglog_png(curves, args.title.value_or("errors against degrees of freedom"), "dofs",
                                          "error", args.output, args.width > 0 ? args.width : 1000,
                                          args.height > 0 ? args.height : 700);
  } else if (args.sorted_quality) {
    std::vector<render_picture::QualityCurve> curves;
    for (std::size_t i = 0; i < args.inputs.size(); i++) {
      vtkSmartPointer<vtkUnstructuredGrid> grid = vtu_io::read_grid(args.inputs[i]);
      curves.push_back({args.labels.empty() ? file_name(args.inputs[i]) : args.labels[i],
                        cell_values(grid, args.picture.array, args.inputs[i])});
    }
    const std::string title = args.title.value_or("cells sorted by " + args.picture.array);
    render_picture::render_sorted_quality_png(curves, title, args.output, args.width > 0 ? args.width : 1000,
                                              args.height > 0 ? args.height : 650);
  } else {
    vtkSmartPointer<vtkUnstructuredGrid> grid = vtu_io::read_grid(args.inputs[0]);
    render_picture::MeshPicture picture = args.picture;
    picture.title = args.title.value_or(file_name(args.inputs[0]));
    picture.subtitle = render_picture::array_summary(grid, picture.array);
    if (args.width > 0) {
      picture.width = args.width;
      picture.height = args.height;
    }
    render_picture::render_mesh_png(grid, picture, args.output);
  }
  std::cout << "igaparam_render: wrote " << args.output << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);  // VTK errors are reported as ours
  std::optional<Arguments> args;
  try {
    args = parse_arguments(argc, argv);
  } catch (const UsageError& e) {
    std::cerr << "igaparam_render: " << e.what() << "\n\n" << kUsage;
    return 2;
  }
  if (!args) {
    std::cout << kUsage;
    return 0;
  }
  try {
    return run(*args);
  } catch (const render_picture::NoDisplayError& e) {
    std::cerr << "igaparam_render: " << e.what() << "\n";
    return kNoDisplayExit;
  } catch (const std::exception& e) {
    std::cerr << "igaparam_render: " << e.what() << "\n";
  }
  return 1;
}
