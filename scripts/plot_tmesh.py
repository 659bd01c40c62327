#!/usr/bin/env python3
"""Draws a planar T-mesh .vtu (polygon cells with a `quality` cell array) as a PNG.

Usage: python3 scripts/plot_tmesh.py IN.vtu OUT.png   (needs meshio, matplotlib, numpy)
"""
import sys

import matplotlib
import meshio
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402


def main(source, target):
    mesh = meshio.read(source)
    polygons = [mesh.points[cell, :2] for block in mesh.cells for cell in block.data]
    quality = np.concatenate([np.ravel(a) for a in mesh.cell_data["quality"]])
    fig, ax = plt.subplots(figsize=(7, 7))
    cells = PolyCollection(polygons, array=quality, cmap="viridis", edgecolors="k", linewidths=0.2)
    cells.set_clim(0.0, 1.0)
    ax.add_collection(cells)
    ax.autoscale()
    ax.set_aspect("equal")
    fig.colorbar(cells, label="cell quality (1 = parametric shape)")
    fig.savefig(target, dpi=70, bbox_inches="tight")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
