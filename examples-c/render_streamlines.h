// render_streamlines.h: the streamline picture of a wind field over a terrain, with VTK
// (vtkStreamTracer on the sampled field, tubes coloured by speed, the terrain shaded by
// elevation), rendered offscreen; and the conversion of a sampled grid to VTK.

#ifndef IGAPARAM_RENDER_STREAMLINES_H
#define IGAPARAM_RENDER_STREAMLINES_H

#include <vtkAlgorithmOutput.h>
#include <vtkCellType.h>
#include <vtkOutlineSource.h>
#include <vtkStreamTracer.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>
#include <vtkTrivialProducer.h>
#include <vtkTubeFilter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include "iga/sample.h"
#include "render_picture.h"

namespace render_streamlines {

/// The sampled grid as a VTK unstructured grid (hexahedra or quads, point data: the fields).
inline vtkSmartPointer<vtkUnstructuredGrid> to_vtk(const iga::SampledGrid &g) {
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  for (size_t i = 0; i + 2 < g.points.size(); i += 3) points->InsertNextPoint(&g.points[i]);
  grid->SetPoints(points);
  const size_t per_cell = g.d == 2 ? 4 : 8;
  grid->Allocate(static_cast<vtkIdType>(g.cells.size() / per_cell));
  for (size_t c = 0; c < g.cells.size(); c += per_cell) {
    vtkIdType ids[8];
    for (size_t k = 0; k < per_cell; k++) ids[k] = static_cast<vtkIdType>(g.cells[c + k]);
    grid->InsertNextCell(g.d == 2 ? VTK_QUAD : VTK_HEXAHEDRON, static_cast<vtkIdType>(per_cell), ids);
  }
  for (const auto &f : g.fields) {
    vtkNew<vtkDoubleArray> array;
    array->SetName(f.name.c_str());
    array->SetNumberOfComponents(f.components);
    for (size_t i = 0; i < f.values.size(); i += f.components) array->InsertNextTuple(&f.values[i]);
    grid->GetPointData()->AddArray(array);
  }
  return grid;
}

/// Writes the grid as binary VTK XML (.vtu).
inline void write_vtu(vtkUnstructuredGrid *grid, const std::string &path) {
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(grid);
  if (writer->Write() != 1) throw std::runtime_error(path + ": VTK cannot write it");
}

/// What render_png draws.
struct Picture {
  std::string title, subtitle;
  int width = 1200, height = 800;
  double stretch = 1.0;                  // vertical exaggeration
  double azimuth = -35, elevation = 25;  // camera, degrees, looking from the south-west upwind
};

namespace detail {

// The n × n grid of terrain points (row-major, 3 values each) as a quad surface with point data
// `elevation`.
inline vtkSmartPointer<vtkPolyData> terrain_surface(const std::vector<double> &xyz, int n) {
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> elevation;
  elevation->SetName("elevation");
  for (size_t i = 0; i + 2 < xyz.size(); i += 3) {
    points->InsertNextPoint(&xyz[i]);
    elevation->InsertNextValue(xyz[i + 2]);
  }
  vtkNew<vtkCellArray> quads;
  for (int j = 0; j + 1 < n; j++)
    for (int i = 0; i + 1 < n; i++) {
      const vtkIdType v = j * n + i, ids[4] = {v, v + 1, v + n + 1, v + n};
      quads->InsertNextCell(4, ids);
    }
  poly->SetPoints(points);
  poly->SetPolys(quads);
  poly->GetPointData()->SetScalars(elevation);
  return poly;
}

// A pipeline output scaled vertically by `stretch`.
inline vtkSmartPointer<vtkTransformPolyDataFilter> stretched(vtkAlgorithmOutput *input, double stretch) {
  vtkNew<vtkTransform> scale;
  scale->Scale(1, 1, stretch);
  auto filter = vtkSmartPointer<vtkTransformPolyDataFilter>::New();
  filter->SetTransform(scale);
  filter->SetInputConnection(input);
  return filter;
}

// Earth colours from low (green) to high (brown, light grey).
inline vtkSmartPointer<vtkLookupTable> terrain_colours(double lo, double hi) {
  vtkNew<vtkColorTransferFunction> ctf;
  ctf->AddRGBPoint(0.0, 0.33, 0.55, 0.33);
  ctf->AddRGBPoint(0.5, 0.72, 0.66, 0.45);
  ctf->AddRGBPoint(1.0, 0.92, 0.9, 0.86);
  auto table = vtkSmartPointer<vtkLookupTable>::New();
  table->SetNumberOfTableValues(256);
  for (int i = 0; i < 256; i++) {
    double rgb[3];
    ctf->GetColor(i / 255.0, rgb);
    table->SetTableValue(i, rgb[0], rgb[1], rgb[2], 1.0);
  }
  table->SetTableRange(lo, hi);
  return table;
}

}  // namespace detail

namespace detail {

// The streamlines of the point vectors `u` of `grid` from the seeds, scaled vertically by
// `stretch`, as tubes.
inline vtkSmartPointer<vtkTubeFilter> streamline_tubes(vtkUnstructuredGrid *grid, const std::vector<double> &seeds,
                                                       double stretch, double diagonal) {
  vtkNew<vtkPolyData> seed_points;
  vtkNew<vtkPoints> points;
  for (size_t i = 0; i + 2 < seeds.size(); i += 3) points->InsertNextPoint(&seeds[i]);
  seed_points->SetPoints(points);
  vtkNew<vtkStreamTracer> tracer;
  tracer->SetInputData(grid);
  tracer->SetSourceData(seed_points);
  tracer->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "u");
  tracer->SetInterpolatorTypeToCellLocator();  // the sampled elements do not share their points
  tracer->SetIntegratorTypeToRungeKutta45();
  tracer->SetIntegrationDirectionToForward();
  tracer->SetMaximumPropagation(3 * diagonal);
  tracer->SetInitialIntegrationStep(0.2);
  tracer->SetMaximumNumberOfSteps(20000);
  tracer->SetComputeVorticity(false);
  auto lines = stretched(tracer->GetOutputPort(), stretch);
  auto tubes = vtkSmartPointer<vtkTubeFilter>::New();
  tubes->SetInputConnection(lines->GetOutputPort());
  tubes->SetRadius(0.0025 * diagonal);
  tubes->SetNumberOfSides(10);
  tubes->Update();
  if (tubes->GetOutput()->GetNumberOfPoints() == 0) throw std::runtime_error("no streamline could be traced");
  return tubes;
}

// Adds the tubes coloured by the speed |u| along them; returns the colour table.
inline vtkSmartPointer<vtkLookupTable> add_tubes(vtkRenderer *renderer, vtkTubeFilter *tubes) {
  double speed[2];
  tubes->GetOutput()->GetPointData()->GetArray("u")->GetRange(speed, -1);
  auto colours = render_picture::detail::viridis(speed[0], speed[1]);
  colours->SetVectorModeToMagnitude();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(tubes->GetOutputPort());
  mapper->SetLookupTable(colours);
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray("u");
  mapper->SetScalarRange(speed);
  mapper->ScalarVisibilityOn();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  return colours;
}

// Adds the terrain (n × n points), shaded by elevation over [lo, hi].
inline void add_terrain(vtkRenderer *renderer, const std::vector<double> &terrain, int n, double stretch, double lo,
                        double hi) {
  vtkNew<vtkTrivialProducer> ground;
  ground->SetOutput(terrain_surface(terrain, n));
  auto ground_stretched = stretched(ground->GetOutputPort(), stretch);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(ground_stretched->GetOutputPort());
  mapper->SetLookupTable(terrain_colours(lo, hi));
  mapper->UseLookupTableScalarRangeOn();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetAmbient(0.35);
  actor->GetProperty()->SetDiffuse(0.7);
  renderer->AddActor(actor);
}

// Adds the outline of the box `bounds` (already stretched).
inline void add_outline(vtkRenderer *renderer, const double *bounds) {
  vtkNew<vtkOutlineSource> outline;
  outline->SetBounds(bounds[0], bounds[1], bounds[2], bounds[3], bounds[4], bounds[5]);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(outline->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.4, 0.4, 0.4);
  renderer->AddActor(actor);
}

}  // namespace detail

/// Draws the streamlines of the point vectors `u` of `grid` from the seeds (3 values each)
/// over the terrain (an n × n grid of points) to the PNG `path`: the view holds the air from
/// the terrain up to a third above the highest seed (the air far above is uniform), framed by
/// its outline. Throws NoDisplayError when no display can be opened.
inline void render_png(vtkUnstructuredGrid *grid, const std::vector<double> &seeds, const std::vector<double> &terrain,
                       int n, const Picture &picture, const std::string &path) {
  render_picture::require_display();
  namespace rd = render_picture::detail;
  double bounds[6];
  grid->GetBounds(bounds);
  const double diagonal = std::sqrt(std::pow(bounds[1] - bounds[0], 2) + std::pow(bounds[3] - bounds[2], 2) +
                                    std::pow(bounds[5] - bounds[4], 2));
  const auto tubes = detail::streamline_tubes(grid, seeds, picture.stretch, diagonal);
  // The scene in the band between the colour bar and the titles, drawn over the whole window's
  // renderer, which holds those.
  vtkNew<vtkRenderer> renderer, overlay;
  renderer->SetBackground(1, 1, 1);
  renderer->SetViewport(0.0, 0.14, 1.0, picture.subtitle.empty() ? 0.92 : 0.88);
  overlay->SetBackground(1, 1, 1);
  const auto speed_colours = detail::add_tubes(renderer, tubes);
  detail::add_terrain(renderer, terrain, n, picture.stretch, bounds[4], bounds[4] + 0.15 * (bounds[5] - bounds[4]));
  double top = bounds[4];
  for (size_t i = 2; i < seeds.size(); i += 3) top = std::max(top, seeds[i]);
  top = std::min(bounds[5], top + 0.35 * (top - bounds[4]));
  double view[6] = {bounds[0], bounds[1], bounds[2], bounds[3], bounds[4] * picture.stretch, top * picture.stretch};
  detail::add_outline(renderer, view);
  rd::add_colour_bar(overlay, speed_colours, "wind speed |u| (units of the initial wind)", picture.height);
  rd::add_title_lines(overlay, picture.title, picture.subtitle, picture.height);

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(picture.width, picture.height);
  window->AddRenderer(overlay);
  window->AddRenderer(renderer);
  vtkCamera *camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, -1, 0);
  camera->SetViewUp(0, 0, 1);
  camera->Azimuth(picture.azimuth);
  camera->Elevation(picture.elevation);
  camera->OrthogonalizeViewUp();
  renderer->ResetCamera(view);
  camera->Zoom(1.1);
  renderer->ResetCameraClippingRange();
  rd::write_png(window, path);
}

}  // namespace render_streamlines

#endif  // IGAPARAM_RENDER_STREAMLINES_H
