#!/usr/bin/env python3
"""Draws the boundary of a solid T-mesh .vtu (hexahedra with `parametric` point data and a
`quality` cell array) as a PNG: the cell faces on the parametric cube's boundary, coloured by the
quality of their cell.

Usage: python3 scripts/plot_solid_tmesh.py IN.vtu OUT.png [ELEVATION AZIMUTH]
(needs meshio, matplotlib, numpy)
"""
import sys

import matplotlib
import meshio
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

# The faces of a VTK hexahedron, by corner.
HEX_FACES = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [0, 4, 7, 3], [1, 2, 6, 5]]


def main(source, target, elevation=20.0, azimuth=-60.0):
    mesh = meshio.read(source)
    uvw = mesh.point_data["parametric"]
    quality = np.concatenate([np.ravel(a) for a in mesh.cell_data["quality"]])
    hexes = np.concatenate([block.data for block in mesh.cells if block.type == "hexahedron"])
    polygons, colours = [], []
    for cell, q in zip(hexes, quality):
        for face in HEX_FACES:
            corners = cell[face]
            p = uvw[corners]
            # A boundary face: all four corners share a coordinate equal to 0 or 1.
            if any(np.all(p[:, k] == v) for k in range(3) for v in (0.0, 1.0)):
                polygons.append(mesh.points[corners])
                colours.append(q)
    fig = plt.figure(figsize=(8, 7))
    ax = fig.add_subplot(projection="3d")
    faces = Poly3DCollection(polygons, array=np.array(colours), cmap="viridis",
                             edgecolors="k", linewidths=0.15)
    faces.set_clim(0.0, 1.0)
    ax.add_collection3d(faces)
    lo, hi = mesh.points.min(axis=0), mesh.points.max(axis=0)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(hi - lo)
    ax.view_init(elev=elevation, azim=azimuth)
    ax.set_axis_off()
    fig.colorbar(faces, label="cell quality (1 = parametric shape)", shrink=0.6)
    fig.savefig(target, dpi=80, bbox_inches="tight")


if __name__ == "__main__":
    if len(sys.argv) not in (3, 5):
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], *map(float, sys.argv[3:]))
