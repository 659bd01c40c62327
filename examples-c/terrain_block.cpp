// terrain_block.cpp: new lid height and flat terrain of a terrain block's faces.

#include "terrain_block.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

namespace terrain_block {

namespace {

using face_files::Face;

enum { kZmin = 4, kZmax = 5 };

// The terrain edge along a wall: (horizontal coordinate, terrain height) of the wall's vertices
// shared with the terrain face, sorted, and the height at any horizontal coordinate by linear
// interpolation (exact at the edge's own vertices).
class TerrainEdge {
 public:
  TerrainEdge(const Face &wall, int axis, const std::set<std::array<double, 3>> &terrain) : axis_(axis) {
    for (size_t i = 0; i < wall.xyz.size(); i += 3) {
      const std::array<double, 3> p{wall.xyz[i], wall.xyz[i + 1], wall.xyz[i + 2]};
      if (terrain.count(p)) edge_.emplace_back(p[axis], p[2]);
    }
    std::sort(edge_.begin(), edge_.end());
    if (edge_.size() < 2) throw std::runtime_error("a wall shares fewer than two vertices with the terrain (zmin)");
  }

  double height(const double *p) const {
    const double s = p[axis_];
    auto it = std::lower_bound(edge_.begin(), edge_.end(), std::make_pair(s, -HUGE_VAL));
    if (it != edge_.end() && it->first == s) return it->second;
    if (it == edge_.begin() || it == edge_.end())
      throw std::runtime_error("a wall vertex lies beyond the ends of its terrain edge");
    const auto &[s1, t1] = *it;
    const auto &[s0, t0] = *(it - 1);
    return t0 + (t1 - t0) * (s - s0) / (s1 - s0);
  }

 private:
  int axis_;
  std::vector<std::pair<double, double>> edge_;
};

}  // namespace

double lid_height(const std::vector<Face> &faces) {
  if (faces.size() != 6 || faces[kZmax].xyz.empty()) throw std::runtime_error("a terrain block has six faces");
  return faces[kZmax].xyz[2];
}

void reshape(std::vector<Face> &faces, double lid, bool flat) {
  const double old_lid = lid_height(faces);
  for (size_t i = 2; i < faces[kZmax].xyz.size(); i += 3)
    if (faces[kZmax].xyz[i] != old_lid) throw std::runtime_error("the lid (zmax) is not flat");
  std::set<std::array<double, 3>> terrain;
  double lowest = HUGE_VAL, highest = -HUGE_VAL;
  const std::vector<double> &ground = faces[kZmin].xyz;
  for (size_t i = 0; i < ground.size(); i += 3) {
    terrain.insert({ground[i], ground[i + 1], ground[i + 2]});
    lowest = std::min(lowest, ground[i + 2]);
    highest = std::max(highest, ground[i + 2]);
  }
  if (!(old_lid > highest) || !(lid > highest))
    throw std::runtime_error("the lid must lie above the terrain's highest point (" + std::to_string(highest) + ")");
  for (int f = 0; f < 4; f++) {
    const TerrainEdge edge(faces[f], f < 2 ? 1 : 0, terrain);  // xmin/xmax walls run along y
    std::vector<double> &xyz = faces[f].xyz;
    for (size_t i = 0; i < xyz.size(); i += 3) {
      double &z = xyz[i + 2];
      if (z == old_lid) {
        z = lid;
        continue;
      }
      // An increasing affine map of each vertical line (some wall vertices next to a jagged
      // terrain edge lie below the edge's chords: they stay below them).
      const double t = edge.height(&xyz[i]), target = flat ? lowest : t;
      z = target + (z - t) * (lid - target) / (old_lid - t);
    }
  }
  for (size_t i = 2; i < faces[kZmax].xyz.size(); i += 3) faces[kZmax].xyz[i] = lid;
  if (flat)
    for (size_t i = 2; i < faces[kZmin].xyz.size(); i += 3) faces[kZmin].xyz[i] = lowest;
}

std::vector<Face> gaussian_hill(double side, double height, double radius, double lid, int n) {
  if (!(side > 0.0) || !(radius > 0.0) || !(height >= 0.0) || !(lid > height) || n < 2)
    throw std::runtime_error("a hill needs side > 0, radius > 0, 0 <= height < lid and n >= 2");
  auto terrain = [=](double x, double y) {
    const double dx = x - 0.5 * side, dy = y - 0.5 * side;
    return height * std::exp(-(dx * dx + dy * dy) / (radius * radius));
  };
  std::vector<double> g(n + 1);
  for (int i = 0; i <= n; i++) g[i] = side * i / n;
  // The face through the grid points point(i, j), i, j = 0..n.
  auto grid_face = [&](auto point) {
    Face f;
    for (int j = 0; j <= n; j++)
      for (int i = 0; i <= n; i++) {
        const std::array<double, 3> p = point(i, j);
        f.xyz.insert(f.xyz.end(), p.begin(), p.end());
      }
    for (int j = 0; j < n; j++)
      for (int i = 0; i < n; i++) {
        const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n) + 2, d = a + uint32_t(n) + 1;
        f.triangles.insert(f.triangles.end(), {a, b, c, a, c, d});
      }
    return f;
  };
  // A wall: horizontal position (x(i), y(i)), heights from the terrain up to the lid.
  auto wall = [&](auto x, auto y) {
    return grid_face([&, x, y](int i, int j) {
      const double t = terrain(x(i), y(i));
      return std::array<double, 3>{x(i), y(i), j == n ? lid : t + (lid - t) * j / n};
    });
  };
  auto at = [&](int i) { return g[i]; };
  auto zero = [](int) { return 0.0; };
  auto far = [side](int) { return side; };
  return {wall(zero, at),
          wall(far, at),
          wall(at, zero),
          wall(at, far),
          grid_face([&](int i, int j) { return std::array<double, 3>{g[i], g[j], terrain(g[i], g[j])}; }),
          grid_face([&](int i, int j) { return std::array<double, 3>{g[i], g[j], lid}; })};
}

}  // namespace terrain_block
