// terrain_block.h: reshaping the six faces of a block of air above a terrain (xmin, xmax, ymin,
// ymax: vertical walls; zmin: the terrain; zmax: a flat lid): a new lid height, and optionally a
// flat terrain, with the faces' shared edges kept identical.

#ifndef IGAPARAM_TERRAIN_BLOCK_H
#define IGAPARAM_TERRAIN_BLOCK_H

#include <vector>

#include "face_files.h"

namespace terrain_block {

/// Moves the lid (zmax, which must be flat) to height `lid` and stretches the walls between
/// the terrain and the lid: a wall vertex at height z above the terrain edge height t at its
/// horizontal position (the terrain edge, the wall's vertices shared with zmin, interpolated
/// linearly along the wall) goes to t' + (z − t)(lid − t')/(old lid − t), so that the wall's
/// bottom edge stays on the terrain, its top edge meets the new lid and the edges shared by two
/// walls move alike. With `flat`, the terrain is replaced by the plane at its lowest height
/// (t' = that height; else t' = t). Throws std::runtime_error when the faces are not such a
/// block or the lid would not lie above the terrain.
void reshape(std::vector<face_files::Face> &faces, double lid, bool flat);

/// A synthetic block: the square [0, side]² on the plain z = 0 with a Gaussian hill
/// z = height · exp(−r²/radius²) at its centre, vertical walls and the flat lid z = lid, each
/// face an n × n grid of quads split in two triangles (the walls' vertices evenly spaced between
/// the terrain and the lid). Its rim is flat to height · exp(−side²/(4 radius²)).
std::vector<face_files::Face> gaussian_hill(double side, double height, double radius, double lid, int n);

/// The lid's height: the z of the zmax face's first vertex.
double lid_height(const std::vector<face_files::Face> &faces);

}  // namespace terrain_block

#endif  // IGAPARAM_TERRAIN_BLOCK_H
