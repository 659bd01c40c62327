"""A G+Smo XML file of a cubic spline map of the unit cube, written by hand (the Python bindings
fit only planar domains, so the 3D tests start from such a file read with
``igaparam.Spline.read_gismo``)."""

import numpy as np

# Level-0 knots in every direction: two spans, so five functions per direction.
KNOTS = "0 0 0 0 0.5 1 1 1 1"
GREVILLE_1D = np.array([0, 1 / 6, 1 / 2, 5 / 6, 1])


def cube_greville():
    """The 125 Greville points of the tensor basis, (125, 3), direction 0 fastest (the order
    of the basis functions and of the control points in the file)."""
    w, v, u = np.meshgrid(GREVILLE_1D, GREVILLE_1D, GREVILLE_1D, indexing="ij")
    return np.column_stack([u.ravel(), v.ravel(), w.ravel()])


def write_cube_gismo(path, control):
    """Writes a ``THBSpline3`` geometry with the tensor basis of :data:`KNOTS` and no refined box,
    and the (125, 3) ``control`` points, to ``path``."""
    bases = "".join(
        f'<Basis type="BSplineBasis" index="{k}"><KnotVector degree="3">{KNOTS}</KnotVector></Basis>\n'
        for k in range(3)
    )
    coefs = "\n".join(" ".join(repr(float(x)) for x in row) for row in control)
    path.write_text(
        '<?xml version="1.0" encoding="UTF-8"?>\n<xml>\n<Geometry type="THBSpline3" id="0">\n'
        f'<Basis type="THBSplineBasis3">\n<Basis type="TensorBSplineBasis3">\n{bases}</Basis>\n</Basis>\n'
        f'<coefs geoDim="3">\n{coefs}\n</coefs>\n</Geometry>\n</xml>\n'
    )
