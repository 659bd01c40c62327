// render_picture.h: PNG pictures of .vtu meshes and sorted-quality charts with VTK, rendered
// offscreen. Shared by igaparam_render and igaparam_relocate (--png).
//
// - render_mesh_png: the mesh's surface (2D: its cells; 3D: its outer boundary, optionally cut
//   by a plane to show the inside), coloured by a cell or point array with a colour bar, with the
//   cell edges drawn (curved edges of quadratic cells as curves).
// - render_sorted_quality_png: the quality of every cell sorted ascending, one curve per mesh.
//
// VTK as packaged by Debian renders through X: a display is needed (under `xvfb-run` when there
// is none). display_available() says whether one can be opened; the functions throw
// NoDisplayError otherwise, since VTK would abort the program.

#ifndef IGAPARAM_RENDER_PICTURE_H
#define IGAPARAM_RENDER_PICTURE_H

#include <dlfcn.h>

#include <vtkActor.h>
#include <vtkAxis.h>
#include <vtkCamera.h>
#include <vtkCell.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkColorTransferFunction.h>
#include <vtkContextScene.h>
#include <vtkContextActor.h>
#include <vtkDataArray.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkDoubleArray.h>
#include <vtkExtractCells.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnstructuredGrid.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace render_picture {

/// No X display can be opened: nothing can be rendered.
struct NoDisplayError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Whether an X display can be opened (DISPLAY is set and its server answers). Asked through
/// libX11 at run time, the library VTK itself renders with. The probe's connection stays open
/// for the life of the program: closing the last client of a server makes it reset (as Xvfb
/// under xvfb-run does), and VTK's own connection opened during the reset would be broken.
inline bool display_available() {
  static const bool available = [] {
    const char* display = std::getenv("DISPLAY");
    if (display == nullptr || *display == '\0') return false;
    void* x11 = dlopen("libX11.so.6", RTLD_LAZY | RTLD_LOCAL);
    if (x11 == nullptr) return false;
    using OpenFn = void* (*)(const char*);
    auto open = reinterpret_cast<OpenFn>(dlsym(x11, "XOpenDisplay"));
    return open != nullptr && open(nullptr) != nullptr;  // kept open (see above)
  }();
  return available;
}

/// Throws NoDisplayError with the way out unless a display can be opened.
inline void require_display() {
  if (display_available()) return;
  const char* display = std::getenv("DISPLAY");
  throw NoDisplayError(display == nullptr || *display == '\0'
                           ? "no X display to render with (DISPLAY is not set): run under xvfb-run "
                             "(Debian package xvfb)"
                           : std::string("cannot open the X display `") + display +
                                 "`: run under xvfb-run (Debian package xvfb)");
}

/// What render_mesh_png draws.
struct MeshPicture {
  /// Cell array (or, if no cell array has that name, point array) colouring the surface; a vector
  /// array colours by its magnitude. Empty: a plain surface.
  std::string array = "quality";
  /// Colour range; both NaN: the array's range.
  double range_min = NAN, range_max = NAN;
  /// Title above the picture; empty: none.
  std::string title;
  /// A line under the title; empty: none.
  std::string subtitle;
  int width = 1000, height = 750;
  bool edges = true;
  /// 3D: keep only the cells whose centre has coordinate `cut_axis` (0 x, 1 y, 2 z; -1 no cut)
  /// below min + cut_fraction × extent of the mesh's bounding box, to show the inside.
  int cut_axis = -1;
  double cut_fraction = 0.5;
  /// 3D camera: rotations (degrees) of the view from the +z side about the view-up (y) axis and
  /// then the horizontal axis.
  double azimuth = 35, elevation = 25;
  /// Factors multiplying the drawn coordinates per axis (display only, e.g. a terrain's
  /// vertical exaggeration).
  double stretch[3] = {1, 1, 1};
};

namespace detail {

/// A perceptually uniform colour map (viridis), from a few of its samples.
inline vtkSmartPointer<vtkLookupTable> viridis(double lo, double hi) {
  static const double samples[][3] = {{0.267, 0.005, 0.329}, {0.283, 0.141, 0.458}, {0.254, 0.265, 0.530},
                                      {0.207, 0.372, 0.553}, {0.164, 0.471, 0.558}, {0.128, 0.567, 0.551},
                                      {0.135, 0.659, 0.518}, {0.267, 0.749, 0.441}, {0.478, 0.821, 0.318},
                                      {0.741, 0.873, 0.150}, {0.993, 0.906, 0.144}};
  const int n = static_cast<int>(sizeof samples / sizeof samples[0]);
  vtkNew<vtkColorTransferFunction> ctf;
  for (int i = 0; i < n; i++) ctf->AddRGBPoint(static_cast<double>(i) / (n - 1), samples[i][0], samples[i][1], samples[i][2]);
  auto table = vtkSmartPointer<vtkLookupTable>::New();
  const int colours = 256;
  table->SetNumberOfTableValues(colours);
  for (int i = 0; i < colours; i++) {
    double rgb[3];
    ctf->GetColor(static_cast<double>(i) / (colours - 1), rgb);
    table->SetTableValue(i, rgb[0], rgb[1], rgb[2], 1.0);
  }
  table->SetTableRange(lo, hi);
  return table;
}

/// The quadratic curve through the ends p0, p1 and the middle node pm of an edge, at t in [0, 1].
inline std::array<double, 3> quadratic_edge_point(const double* p0, const double* p1, const double* pm, double t) {
  const double a = 2 * (t - 0.5) * (t - 1), b = 2 * t * (t - 0.5), c = -4 * t * (t - 1);
  return {a * p0[0] + b * p1[0] + c * pm[0], a * p0[1] + b * p1[1] + c * pm[1], a * p0[2] + b * p1[2] + c * pm[2]};
}

/// Collects the edges of `cell` (once each, keyed by their end points) as polylines; quadratic
/// edges become curves of `segments` pieces.
class EdgeCollector {
 public:
  EdgeCollector(vtkUnstructuredGrid* grid, int segments) : grid_(grid), segments_(segments) {}

  void add_edges_of(vtkCell* cell) {
    for (int e = 0; e < cell->GetNumberOfEdges(); e++) add_edge(cell->GetEdge(e));
  }

  vtkSmartPointer<vtkPolyData> polydata() {
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(points_);
    poly->SetLines(lines_);
    return poly;
  }

 private:
  void add_edge(vtkCell* edge) {
    vtkIdList* ids = edge->GetPointIds();
    const vtkIdType n = ids->GetNumberOfIds();
    if (n < 2) return;
    const vtkIdType a = ids->GetId(0), b = ids->GetId(1);
    if (!seen_.insert({std::min(a, b), std::max(a, b)}).second) return;
    double p0[3], p1[3];
    grid_->GetPoint(a, p0);
    grid_->GetPoint(b, p1);
    if (n == 3) {  // quadratic edge: ends, then the middle node
      double pm[3];
      grid_->GetPoint(ids->GetId(2), pm);
      lines_->InsertNextCell(segments_ + 1);
      for (int s = 0; s <= segments_; s++) {
        const auto p = quadratic_edge_point(p0, p1, pm, static_cast<double>(s) / segments_);
        lines_->InsertCellPoint(points_->InsertNextPoint(p.data()));
      }
    } else {
      lines_->InsertNextCell(2);
      lines_->InsertCellPoint(points_->InsertNextPoint(p0));
      lines_->InsertCellPoint(points_->InsertNextPoint(p1));
    }
  }

  vtkUnstructuredGrid* grid_;
  int segments_;
  vtkNew<vtkPoints> points_;
  vtkNew<vtkCellArray> lines_;
  std::set<std::pair<vtkIdType, vtkIdType>> seen_;
};

/// The grid's dimension: the largest dimension of its cells.
inline int grid_dimension(vtkUnstructuredGrid* grid) {
  int d = 0;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); c++) d = std::max(d, grid->GetCell(c)->GetCellDimension());
  return d;
}

/// The edges to draw: of every 2D cell, and of the boundary faces (those of one cell only) of
/// the 3D cells.
inline vtkSmartPointer<vtkPolyData> visible_edges(vtkUnstructuredGrid* grid) {
  EdgeCollector edges(grid, 8);
  std::map<std::vector<vtkIdType>, std::pair<vtkIdType, int>> faces;  // sorted ids -> (cell, face)
  std::map<std::vector<vtkIdType>, int> uses;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); c++) {
    vtkCell* cell = grid->GetCell(c);
    if (cell->GetCellDimension() < 3) {
      edges.add_edges_of(cell);
      continue;
    }
    for (int f = 0; f < cell->GetNumberOfFaces(); f++) {
      vtkIdList* ids = cell->GetFace(f)->GetPointIds();
      std::vector<vtkIdType> key(ids->GetPointer(0), ids->GetPointer(0) + ids->GetNumberOfIds());
      std::sort(key.begin(), key.end());
      faces.emplace(key, std::make_pair(c, f));
      uses[key]++;
    }
  }
  for (const auto& [key, where] : faces) {
    if (uses[key] == 1) edges.add_edges_of(grid->GetCell(where.first)->GetFace(where.second));
  }
  return edges.polydata();
}

/// The cells of `grid` whose centre lies below the cut (see MeshPicture::cut_axis).
inline vtkSmartPointer<vtkUnstructuredGrid> cut_grid(vtkUnstructuredGrid* grid, int axis, double fraction) {
  double bounds[6];
  grid->GetBounds(bounds);
  const double limit = bounds[2 * axis] + fraction * (bounds[2 * axis + 1] - bounds[2 * axis]);
  vtkNew<vtkIdList> keep;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); c++) {
    double cb[6];
    grid->GetCell(c)->GetBounds(cb);
    if (0.5 * (cb[2 * axis] + cb[2 * axis + 1]) < limit) keep->InsertNextId(c);
  }
  if (keep->GetNumberOfIds() == 0) throw std::runtime_error("the cut keeps no cell");
  vtkNew<vtkExtractCells> extract;
  extract->SetInputData(grid);
  extract->SetCellList(keep);
  extract->Update();
  auto out = vtkSmartPointer<vtkUnstructuredGrid>::New();
  out->ShallowCopy(extract->GetOutput());
  return out;
}

/// Renders `window` (offscreen) and writes what it shows to `path`.
inline void write_png(vtkRenderWindow* window, const std::string& path) {
  window->Render();
  vtkNew<vtkWindowToImageFilter> image;
  image->SetInput(window);
  image->SetInputBufferTypeToRGB();
  image->ReadFrontBufferOff();
  image->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputConnection(image->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != 0) throw std::runtime_error("cannot write " + path);
}

inline void style_text(vtkTextProperty* text, int size, bool bold = false) {
  text->SetColor(0.1, 0.1, 0.1);
  text->SetFontSize(size);
  text->SetBold(bold);
  text->SetItalic(false);
  text->SetShadow(false);
  text->SetFontFamilyToArial();
}

/// The title and subtitle lines (either may be empty) at the top of the renderer's viewport,
/// for a window `height` pixels high.
inline void add_title_lines(vtkRenderer* renderer, const std::string& title, const std::string& subtitle,
                            int height) {
  int line = 0;
  for (const std::string* text : {&title, &subtitle}) {
    if (text->empty()) continue;
    vtkNew<vtkTextActor> actor;
    actor->SetInput(text->c_str());
    style_text(actor->GetTextProperty(), height / (line == 0 ? 28 : 38), line == 0);
    actor->GetTextProperty()->SetJustificationToCentered();
    actor->GetTextProperty()->SetVerticalJustificationToTop();
    actor->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
    actor->SetPosition(0.5, line == 0 ? 0.975 : 0.915);
    renderer->AddActor2D(actor);
    line++;
  }
}

/// A horizontal colour bar of `table` across the bottom of the renderer's viewport.
inline void add_colour_bar(vtkRenderer* renderer, vtkScalarsToColors* table, const std::string& title, int height) {
  vtkNew<vtkScalarBarActor> bar;
  bar->SetLookupTable(table);
  bar->SetTitle((" " + title).c_str());
  bar->SetOrientationToHorizontal();
  bar->SetNumberOfLabels(5);
  bar->SetLabelFormat("%.3g");
  bar->SetPosition(0.2, 0.03);
  bar->SetWidth(0.6);
  bar->SetHeight(0.1);
  bar->SetBarRatio(0.35);
  bar->SetTextPositionToPrecedeScalarBar();
  bar->UnconstrainedFontSizeOn();
  style_text(bar->GetTitleTextProperty(), height / 36, true);
  style_text(bar->GetLabelTextProperty(), height / 42);
  renderer->AddActor2D(bar);
}

/// An offscreen window of `width` × `height` pixels whose renderer holds an XY chart with a
/// title and a legend in a corner (vtkChartLegend::LEFT or RIGHT, BOTTOM or TOP). A plain window with the chart
/// in a context actor: a vtkContextView would bring an interactor, which an offscreen window
/// does not want.
struct ChartWindow {
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkContextActor> actor;
  vtkNew<vtkChartXY> chart;

  ChartWindow(int width, int height, const std::string& title, int legend_side, int legend_end) {
    window->SetOffScreenRendering(1);
    window->SetSize(width, height);
    renderer->SetBackground(1, 1, 1);
    window->AddRenderer(renderer);
    renderer->AddActor(actor);
    actor->GetScene()->AddItem(chart);
    chart->SetTitle(title);
    style_text(chart->GetTitleProperties(), height / 30, true);
    chart->SetShowLegend(true);
    chart->GetLegend()->SetHorizontalAlignment(legend_side);
    chart->GetLegend()->SetVerticalAlignment(legend_end);
    chart->GetLegend()->SetLabelSize(height / 36);
  }

  /// Styles the axes' titles, labels and grid.
  void style_axes(int height) {
    for (vtkAxis* axis : {chart->GetAxis(vtkAxis::BOTTOM), chart->GetAxis(vtkAxis::LEFT)}) {
      style_text(axis->GetTitleProperties(), height / 32, true);
      style_text(axis->GetLabelProperties(), height / 38);
      axis->GetGridPen()->SetColor(220, 220, 220, 255);
    }
  }
};

/// Colours of chart curves, in turn.
inline const unsigned char* curve_colour(std::size_t i) {
  static const unsigned char colours[][3] = {{204, 51, 17}, {0, 119, 187}, {0, 153, 136}, {238, 119, 51}, {51, 34, 136}};
  return colours[i % (sizeof colours / sizeof colours[0])];
}

}  // namespace detail

/// The array `name` of `grid`: a cell array, else a point array; nullptr if neither. Sets
/// `on_cells`.
inline vtkDataArray* find_array(vtkDataSet* grid, const std::string& name, bool& on_cells) {
  if (vtkDataArray* a = grid->GetCellData()->GetArray(name.c_str())) {
    on_cells = true;
    return a;
  }
  on_cells = false;
  return grid->GetPointData()->GetArray(name.c_str());
}

/// Names of the grid's cell and point arrays, for messages.
inline std::string array_names(vtkDataSet* grid) {
  std::string names;
  for (vtkFieldData* data : {static_cast<vtkFieldData*>(grid->GetCellData()), static_cast<vtkFieldData*>(grid->GetPointData())}) {
    const bool cells = data == grid->GetCellData();
    for (int i = 0; i < data->GetNumberOfArrays(); i++) {
      if (data->GetArrayName(i) == nullptr) continue;
      names += (names.empty() ? "" : ", ") + std::string(data->GetArrayName(i)) + (cells ? " (cells)" : " (points)");
    }
  }
  return names.empty() ? "none" : names;
}

/// "490 cells, quality min 0.660, mean 0.915": the number of cells and, when the grid has the
/// (scalar) array `name`, its smallest and mean value.
inline std::string array_summary(vtkUnstructuredGrid* grid, const std::string& name) {
  std::string text = std::to_string(grid->GetNumberOfCells()) + " cells";
  bool on_cells = true;
  vtkDataArray* array = name.empty() ? nullptr : find_array(grid, name, on_cells);
  if (array == nullptr || array->GetNumberOfComponents() != 1 || array->GetNumberOfTuples() == 0) return text;
  double sum = 0, least = INFINITY;
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); i++) {
    sum += array->GetTuple1(i);
    least = std::min(least, array->GetTuple1(i));
  }
  char figures[96];
  std::snprintf(figures, sizeof figures, ", %s min %.3f, mean %.3f", name.c_str(), least,
                sum / static_cast<double>(array->GetNumberOfTuples()));
  return text + figures;
}

/// Renders `grid` as described by `picture` to the PNG file `path`. Throws NoDisplayError when
/// no display can be opened, std::runtime_error when the array is missing or writing fails.
inline void render_mesh_png(vtkUnstructuredGrid* input, const MeshPicture& picture, const std::string& path) {
  if (input->GetNumberOfCells() == 0) throw std::runtime_error("the mesh has no cells");
  bool on_cells = true;
  vtkDataArray* array = nullptr;
  if (!picture.array.empty()) {
    array = find_array(input, picture.array, on_cells);
    if (array == nullptr) {
      throw std::runtime_error("no cell or point array `" + picture.array + "`; the mesh has: " + array_names(input));
    }
  }
  require_display();

  const int dimension = detail::grid_dimension(input);
  vtkSmartPointer<vtkUnstructuredGrid> grid = input;
  if (dimension == 3 && picture.cut_axis >= 0) grid = detail::cut_grid(input, picture.cut_axis, picture.cut_fraction);

  vtkNew<vtkDataSetSurfaceFilter> surface;
  surface->SetInputData(grid);
  surface->SetNonlinearSubdivisionLevel(3);  // curved faces of quadratic cells
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(surface->GetOutputPort());
  mapper->SetResolveCoincidentTopologyToPolygonOffset();
  mapper->SetRelativeCoincidentTopologyPolygonOffsetParameters(2, 40);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1, 1, 1);
  renderer->UseFXAAOff();
  vtkNew<vtkActor> surface_actor;
  surface_actor->SetMapper(mapper);
  surface_actor->SetScale(picture.stretch[0], picture.stretch[1], picture.stretch[2]);
  surface_actor->GetProperty()->SetAmbient(dimension == 3 ? 0.35 : 1.0);
  surface_actor->GetProperty()->SetDiffuse(dimension == 3 ? 0.65 : 0.0);
  renderer->AddActor(surface_actor);

  if (array != nullptr) {
    const int component = array->GetNumberOfComponents() > 1 ? -1 : 0;  // -1: magnitude
    double range[2];
    array->GetRange(range, component);
    if (!std::isnan(picture.range_min)) range[0] = picture.range_min;
    if (!std::isnan(picture.range_max)) range[1] = picture.range_max;
    if (!(range[1] > range[0])) range[1] = range[0] + 1e-12;
    auto table = detail::viridis(range[0], range[1]);
    if (component < 0) table->SetVectorModeToMagnitude();
    mapper->SetLookupTable(table);
    mapper->SetScalarRange(range);
    mapper->SetScalarModeToUsePointFieldData();
    if (on_cells) mapper->SetScalarModeToUseCellFieldData();
    mapper->SelectColorArray(picture.array.c_str());
    mapper->SetColorModeToMapScalars();
    mapper->ScalarVisibilityOn();

    detail::add_colour_bar(renderer, table, picture.array + (component < 0 ? " (magnitude)" : ""), picture.height);
  } else {
    mapper->ScalarVisibilityOff();
    surface_actor->GetProperty()->SetColor(0.75, 0.8, 0.9);
  }

  if (picture.edges) {
    vtkNew<vtkPolyDataMapper> edge_mapper;
    edge_mapper->SetInputData(detail::visible_edges(grid));
    edge_mapper->ScalarVisibilityOff();
    edge_mapper->SetResolveCoincidentTopologyToPolygonOffset();
    edge_mapper->SetRelativeCoincidentTopologyLineOffsetParameters(-2, -40);
    vtkNew<vtkActor> edge_actor;
    edge_actor->SetMapper(edge_mapper);
    edge_actor->SetScale(picture.stretch[0], picture.stretch[1], picture.stretch[2]);
    edge_actor->GetProperty()->SetColor(0.1, 0.1, 0.1);
    edge_actor->GetProperty()->SetLineWidth(std::max(1.0f, static_cast<float>(picture.height) / 900.0f));
    edge_actor->GetProperty()->LightingOff();
    edge_actor->GetProperty()->SetOpacity(dimension == 3 ? 0.6 : 0.85);
    renderer->AddActor(edge_actor);
  }

  // The mesh goes into the band [bottom, top] of the window height: below the title lines and
  // above the colour bar.
  const double top = picture.title.empty() ? 0.98 : picture.subtitle.empty() ? 0.9 : 0.85;
  const double bottom = array != nullptr ? 0.15 : 0.02;
  detail::add_title_lines(renderer, picture.title, picture.subtitle, picture.height);

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(picture.width, picture.height);
  window->AddRenderer(renderer);

  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, 0, 1);
  camera->SetViewUp(0, 1, 0);
  if (dimension == 3) {
    camera->Azimuth(picture.azimuth);
    camera->Elevation(picture.elevation);
    camera->OrthogonalizeViewUp();
  } else {
    camera->ParallelProjectionOn();
    surface_actor->GetProperty()->LightingOff();
  }
  renderer->ResetCamera();
  // Fit the mesh into the band [bottom, top] of the window height.
  const double band = top - bottom;
  if (dimension == 3) {
    camera->Zoom(1.1 * band);
  } else {
    double bounds[6];
    grid->GetBounds(bounds);
    const double aspect = static_cast<double>(picture.width) / picture.height;
    const double half = std::max(0.5 * picture.stretch[1] * (bounds[3] - bounds[2]),
                                 0.5 * picture.stretch[0] * (bounds[1] - bounds[0]) / aspect);
    camera->SetParallelScale(half / (0.96 * band));
  }
  // Shift the view so that the mesh's centre comes to the band's centre.
  const double shift = (0.5 - 0.5 * (top + bottom));  // fraction of the window height
  double focal[3], position[3], up[3];
  camera->GetFocalPoint(focal);
  camera->GetPosition(position);
  camera->GetViewUp(up);
  double height_world;
  if (camera->GetParallelProjection()) {
    height_world = 2 * camera->GetParallelScale();
  } else {
    height_world = 2 * camera->GetDistance() * std::tan(0.5 * camera->GetViewAngle() * M_PI / 180);
  }
  for (int k = 0; k < 3; k++) {
    focal[k] += shift * height_world * up[k];
    position[k] += shift * height_world * up[k];
  }
  camera->SetFocalPoint(focal);
  camera->SetPosition(position);
  renderer->ResetCameraClippingRange();

  detail::write_png(window, path);
}

/// One curve of a sorted-quality chart.
struct QualityCurve {
  std::string label;
  std::vector<double> quality;  // one value per cell, any order
};

/// Draws the quality of every cell of each curve sorted ascending against the cell's rank
/// (as a fraction of the cells, so that meshes of different sizes compare) to the PNG `path`.
inline void render_sorted_quality_png(const std::vector<QualityCurve>& curves, const std::string& title,
                                      const std::string& path, int width = 1000, int height = 650) {
  if (curves.empty()) throw std::runtime_error("no quality curve to draw");
  require_display();
  detail::ChartWindow view(width, height, title, vtkChartLegend::RIGHT, vtkChartLegend::BOTTOM);
  vtkChartXY* chart = view.chart;
  std::vector<vtkSmartPointer<vtkTable>> tables;
  for (std::size_t i = 0; i < curves.size(); i++) {
    std::vector<double> sorted = curves[i].quality;
    if (sorted.empty()) throw std::runtime_error("curve `" + curves[i].label + "` has no cells");
    std::sort(sorted.begin(), sorted.end());
    auto table = vtkSmartPointer<vtkTable>::New();
    vtkNew<vtkDoubleArray> x;
    x->SetName("rank");
    vtkNew<vtkDoubleArray> y;
    y->SetName(curves[i].label.c_str());
    const std::size_t n = sorted.size();
    for (std::size_t k = 0; k < n; k++) {
      x->InsertNextValue(n == 1 ? 0.0 : 100.0 * static_cast<double>(k) / static_cast<double>(n - 1));
      y->InsertNextValue(sorted[k]);
    }
    table->AddColumn(x);
    table->AddColumn(y);
    tables.push_back(table);
    vtkPlot* line = chart->AddPlot(vtkChart::LINE);
    line->SetInputData(table, 0, 1);
    const auto* c = detail::curve_colour(i);
    line->SetColor(c[0], c[1], c[2], 255);
    line->SetWidth(3.0);
    line->SetLabel(curves[i].label);
  }
  vtkAxis* x_axis = chart->GetAxis(vtkAxis::BOTTOM);
  x_axis->SetTitle("cells sorted by quality (%)");
  x_axis->SetBehavior(vtkAxis::FIXED);
  x_axis->SetRange(0, 100);
  vtkAxis* y_axis = chart->GetAxis(vtkAxis::LEFT);
  y_axis->SetTitle("quality");
  y_axis->SetBehavior(vtkAxis::FIXED);
  y_axis->SetRange(0, 1.02);
  view.style_axes(height);
  detail::write_png(view.window, path);
}

}  // namespace render_picture

#endif  // IGAPARAM_RENDER_PICTURE_H
