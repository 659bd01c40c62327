// render_convergence.h: log-log charts of errors against degrees of freedom (convergence
// series of igaparam_poisson), rendered offscreen with VTK; and the reading of the series from
// the JSON line a program prints last.

#ifndef IGAPARAM_RENDER_CONVERGENCE_H
#define IGAPARAM_RENDER_CONVERGENCE_H

#include <fstream>
#include <regex>

#include "render_picture.h"

namespace render_convergence {

/// The numbers of the list `"key": [a, b, ...]` in a JSON line (null entries as NaN); empty
/// when the key is absent.
inline std::vector<double> json_numbers(const std::string &json, const std::string &key) {
  const std::regex pattern("\"" + key + "\": *\\[([^\\]]*)\\]");
  std::smatch match;
  std::vector<double> out;
  if (!std::regex_search(json, match, pattern)) return out;
  const std::string list = match[1];
  std::size_t at = 0;
  while (at < list.size()) {
    std::size_t comma = list.find(',', at);
    if (comma == std::string::npos) comma = list.size();
    const std::string item = list.substr(at, comma - at);
    out.push_back(item.find("null") != std::string::npos ? NAN : std::stod(item));
    at = comma + 1;
  }
  return out;
}

/// The last line of a file that starts with `{` (a program's JSON summary).
inline std::string last_json_line(const std::string &path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::string line, json;
  while (std::getline(in, line))
    if (!line.empty() && line[0] == '{') json = line;
  if (json.empty()) throw std::runtime_error(path + " has no JSON line");
  return json;
}

/// One curve of a chart: points (x, y), both positive.
struct Curve {
  std::string label;
  std::vector<double> x, y;
  bool dashed = false;
};

/// Draws the curves on log-log axes to the PNG `path`.
inline void render_loglog_png(const std::vector<Curve> &curves, const std::string &title, const std::string &x_title,
                              const std::string &y_title, const std::string &path, int width = 1000,
                              int height = 700) {
  if (curves.empty()) throw std::runtime_error("no curve to draw");
  render_picture::require_display();
  namespace rd = render_picture::detail;
  rd::ChartWindow view(width, height, title, vtkChartLegend::LEFT, vtkChartLegend::BOTTOM);
  vtkChartXY *chart = view.chart;
  std::vector<vtkSmartPointer<vtkTable>> tables;
  for (std::size_t i = 0; i < curves.size(); i++) {
    auto table = vtkSmartPointer<vtkTable>::New();
    vtkNew<vtkDoubleArray> x, y;
    x->SetName("dofs");
    y->SetName(curves[i].label.c_str());
    for (std::size_t k = 0; k < curves[i].x.size() && k < curves[i].y.size(); k++)
      if (curves[i].x[k] > 0 && curves[i].y[k] > 0) {
        x->InsertNextValue(curves[i].x[k]);
        y->InsertNextValue(curves[i].y[k]);
      }
    if (x->GetNumberOfTuples() == 0) throw std::runtime_error("curve `" + curves[i].label + "` has no positive point");
    table->AddColumn(x);
    table->AddColumn(y);
    tables.push_back(table);
    vtkPlot *line = chart->AddPlot(vtkChart::LINE);
    line->SetInputData(table, 0, 1);
    const auto *c = rd::curve_colour(i);
    line->SetColor(c[0], c[1], c[2], 255);
    line->SetWidth(curves[i].dashed ? 1.5f : 3.0f);
    if (curves[i].dashed) line->GetPen()->SetLineType(vtkPen::DASH_LINE);
    line->SetLabel(curves[i].label);
  }
  vtkAxis *x_axis = chart->GetAxis(vtkAxis::BOTTOM), *y_axis = chart->GetAxis(vtkAxis::LEFT);
  x_axis->SetTitle(x_title);
  y_axis->SetTitle(y_title);
  x_axis->SetLogScale(true);
  y_axis->SetLogScale(true);
  view.style_axes(height);
  rd::write_png(view.window, path);
}

/// The curves of a convergence series: H1 and L2 errors against dofs of the series (keys `dofs`,
/// `h1`, `l2`) and, when present, of the uniform series beside it (`uniform_dofs`, ...), with
/// the optimal H1 slope dofs^(−3/dim) through the series' last point, labels prefixed by
/// `prefix`.
inline std::vector<Curve> convergence_curves(const std::string &json, const std::string &prefix) {
  const bool adaptive = json.find("\"uniform_dofs\"") != std::string::npos;
  std::vector<Curve> curves;
  for (const char *series : {"", "uniform_"}) {
    const std::string s = series;
    const std::vector<double> dofs = json_numbers(json, s + "dofs");
    if (dofs.empty()) continue;
    const std::string name = prefix + (s.empty() ? (adaptive ? "adaptive" : "uniform") : "uniform");
    curves.push_back({name + ", H1 error", dofs, json_numbers(json, s + "h1")});
    curves.push_back({name + ", L2 error", dofs, json_numbers(json, s + "l2")});
  }
  if (curves.empty()) throw std::runtime_error("the JSON line has no `dofs` list");
  const std::regex dim_pattern("\"dim\": *([23])");
  std::smatch match;
  if (std::regex_search(json, match, dim_pattern) && curves[0].x.size() >= 2) {
    const double rate = 3.0 / std::stod(match[1]), x1 = curves[0].x.back(), y1 = curves[0].y.back();
    const double x0 = curves[0].x.front();
    char label[64];
    std::snprintf(label, sizeof label, "slope dofs^-%.3g (optimal H1)", rate);
    curves.push_back({label, {x0, x1}, {y1 * std::pow(x1 / x0, rate), y1}, true});
  }
  return curves;
}

}  // namespace render_convergence

#endif  // IGAPARAM_RENDER_CONVERGENCE_H
