// face_files.h: the six triangulated faces of a solid (xmin, xmax, ymin, ymax, zmin, zmax) read
// from a folder by OpenMesh, and the solid domain made of them. Shared by igaparam_param and
// igaparam_wind.

#ifndef IGAPARAM_FACE_FILES_H
#define IGAPARAM_FACE_FILES_H

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "igaparam.h"

namespace face_files {

namespace fs = std::filesystem;

/// A triangulated face as flat arrays: vertices (3 per vertex), triangles (3 indices each).
struct Face {
  std::vector<double> xyz;
  std::vector<uint32_t> triangles;
};

/// The names of the six faces, in the order of the unit cube's faces.
inline const std::array<const char*, 6>& face_names() {
  static const std::array<const char*, 6> names = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  return names;
}

/// The `v x y z` lines of an OBJ file in double precision, in file order (empty when one of
/// them does not parse).
inline std::vector<double> obj_vertices(const fs::path& path) {
  std::ifstream in(path);
  std::vector<double> xyz;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string key;
    if (!(words >> key) || key != "v") continue;
    double p[3];
    if (!(words >> p[0] >> p[1] >> p[2])) return {};
    xyz.insert(xyz.end(), p, p + 3);
  }
  return xyz;
}

/// Reads one face file (.obj, .off, .stl or .ply) with OpenMesh.
inline Face read_face(const fs::path& path) {
  using TriMesh = OpenMesh::TriMesh_ArrayKernelT<>;
  TriMesh mesh;
  if (!OpenMesh::IO::read_mesh(mesh, path.string()))
    throw std::runtime_error(path.string() + ": OpenMesh cannot read it");
  Face f;
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    f.xyz.insert(f.xyz.end(), {double(p[0]), double(p[1]), double(p[2])});
  }
  for (auto face : mesh.faces()) {
    for (auto v : mesh.fv_range(face)) f.triangles.push_back(uint32_t(v.idx()));
  }
  // OpenMesh's OBJ reader parses coordinates as float: take the file's own digits back when
  // its vertices are OpenMesh's, in the same order, so that the same faces give the same
  // parameterization whichever reader (this one or the library's) is used.
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  if (ext == ".obj") {
    std::vector<double> exact = obj_vertices(path);
    bool same = exact.size() == f.xyz.size();
    for (size_t i = 0; same && i < exact.size(); i++)
      same = std::abs(exact[i] - f.xyz[i]) <= 1e-6 * std::abs(exact[i]);
    if (same) f.xyz = std::move(exact);
  }
  return f;
}

/// The face file `name.ext` of a folder, for the first extension present.
inline fs::path face_file(const fs::path& dir, const std::string& name) {
  for (const char* ext : {".obj", ".off", ".stl", ".ply"}) {
    fs::path p = dir / (name + ext);
    if (fs::exists(p)) return p;
  }
  throw std::runtime_error(dir.string() + ": no " + name + ".obj/.off/.stl/.ply");
}

/// The six faces of a folder, every coordinate multiplied by its axis' factor of `scale`
/// (NULL: kept).
inline std::vector<Face> read_faces(const fs::path& dir, const std::array<double, 3>* scale) {
  std::vector<Face> faces;
  for (const char* name : face_names()) {
    faces.push_back(read_face(face_file(dir, name)));
    if (scale)
      for (size_t i = 0; i < faces.back().xyz.size(); i++) faces.back().xyz[i] *= (*scale)[i % 3];
  }
  return faces;
}

/// Prints a note when the faces' bounding box is over 100 times longer in one axis than in
/// another: a sign of axes in different units (degrees and km, say), which distort Floater's maps.
inline void warn_if_anisotropic(const std::vector<Face>& faces) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const Face& f : faces)
    for (size_t i = 0; i < f.xyz.size(); i++) {
      lo[i % 3] = std::min(lo[i % 3], f.xyz[i]);
      hi[i % 3] = std::max(hi[i % 3], f.xyz[i]);
    }
  double w[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
  double shortest = std::min({w[0], w[1], w[2]}), longest = std::max({w[0], w[1], w[2]});
  if (longest > 100 * shortest)
    std::printf("note: the faces span %.4g x %.4g x %.4g; if the axes have different units, give "
                "them one with --scale SX,SY,SZ\n",
                w[0], w[1], w[2]);
}

/// Creates the solid bounded by the six faces (igaparam_domain_new_solid_from_triangulations).
inline igaparam_status new_solid(const std::vector<Face>& faces, igaparam_domain** out) {
  size_t nv[6], nt[6];
  const double* xyz[6];
  const uint32_t* tri[6];
  for (int f = 0; f < 6; f++) {
    nv[f] = faces[f].xyz.size() / 3;
    nt[f] = faces[f].triangles.size() / 3;
    xyz[f] = faces[f].xyz.data();
    tri[f] = faces[f].triangles.data();
  }
  return igaparam_domain_new_solid_from_triangulations(nv, xyz, nt, tri, out);
}

/// Three positive finite factors "SX,SY,SZ"; throws a std::logic_error otherwise.
inline std::array<double, 3> parse_scale(const std::string& v) {
  std::array<double, 3> f{};
  size_t at = 0;
  for (int k = 0; k < 3; k++) {
    size_t used = 0;
    f[k] = std::stod(v.substr(at), &used);
    if (!std::isfinite(f[k]) || f[k] <= 0) throw std::out_of_range(v);
    at += used;
    if (k < 2 && (at >= v.size() || v[at++] != ',')) throw std::invalid_argument(v);
  }
  if (at != v.size()) throw std::invalid_argument(v);
  return f;
}

}  // namespace face_files

#endif  // IGAPARAM_FACE_FILES_H
