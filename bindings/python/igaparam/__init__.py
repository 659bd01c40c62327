"""igaparam: relocation of the free nodes of quadrilateral/hexahedral finite-element meshes
after their boundary moves, T-mesh parameterizations of planar domains and solids from their
boundary, and their cubic THB-spline maps (ctypes bindings of the C API, with numpy arrays).

Example::

    import numpy as np, igaparam
    with igaparam.Mesh("Q9", points, cells) as mesh:   # points (n, 3), cells (m, 9)
        mesh.set_fixed(mask)                           # (n,) uint8: bit 0 x, 1 y, 2 z
        mesh.move_nodes(new_xyz, indices=boundary)     # (k, 3), (k,)
        report = mesh.relocate()
        xyz = mesh.positions                           # (n, 3)

    with igaparam.Domain.from_file("male_bdry.xml") as domain:
        report = domain.build()                        # report.invalid_cells == 0
        xy, quality = domain.physical_vertices, domain.cell_quality
        with igaparam.Spline.fit(domain) as spline:    # cubic THB spline map of [0,1]^2
            xy = spline.evaluate(domain.parametric_vertices)   # (n, 2) -> (n, 2)
            assert spline.check_validity().certified_positive

The shared library is found through the environment variable ``IGAPARAM_LIBRARY`` (its path),
else next to this package, else with ``ctypes.util.find_library("igaparam")``.
"""

from ._boundary import Curve, Surface
from ._capi import CellType, FitChoice, FitRule, Stage, Status
from ._domain import Domain, DomainReport, UpdateReport
from ._mesh import IgaparamError, Mesh, RelocateReport, cell_type_code, node_coordinates, nodes_per_cell, version
from ._refit import RefitReport
from ._spline import AdaptReport, FitReport, QualityBound, Spline, ValidityReport

__version__ = "0.1.0"

__all__ = [
    "AdaptReport",
    "CellType",
    "Curve",
    "Domain",
    "DomainReport",
    "FitChoice",
    "FitReport",
    "FitRule",
    "IgaparamError",
    "Mesh",
    "QualityBound",
    "RefitReport",
    "RelocateReport",
    "Spline",
    "Stage",
    "Status",
    "Surface",
    "UpdateReport",
    "ValidityReport",
    "cell_type_code",
    "node_coordinates",
    "nodes_per_cell",
    "version",
]
