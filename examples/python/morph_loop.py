"""A shape-optimization loop on a spline map: the boundary of a domain morphs in steps, and at
every step the domain's T-mesh follows it (``Domain.update``, the tree kept) and the spline map
is refitted in the same space (``Spline.refit``): the same basis functions and elements, so a
solver's matrices keep their pattern.

Two morphs of the bundled boundaries (G+Smo XML files, read here into arrays):

- a planar domain of four curves (``puzzle3_bdry.xml``): the knob on its first curve (control
  points 9 to 26) grows by up to 20% about the point where it joins the side;
- a solid of six surfaces (``duck3d_BRep.xml``): the inner control points of its last surface are
  scaled about their centroid by up to 10% in the middle, tapering to 0 at its edges, so that the
  surfaces still share their edges.

Prints one row per step (basis count, certification, smallest sampled q_S, seconds of the update
and the refit), then one JSON line. Exits with 1 if a step changed the basis or the elements, or
left the map uncertified.

With ``--check-sensitivities`` (planar boundaries), it checks instead the derivative of
``J = |P|^2 / 2`` of the spline's control points P along the knob's growth: by the adjoint with
respect to the curves' control points (``Spline.adjoint_controls``, one product) against central
differences of update + refit. The domain is built with the Newton polish and without seam
relief offsets, the state the sensitivities differentiate.

Usage: python morph_loop.py BOUNDARY.xml [--steps 20] [--threads 0] [--check-sensitivities]
"""

import argparse
import json
import sys
import time
import xml.etree.ElementTree as ET

import numpy as np

import igaparam


def _numbers(element):
    return np.array(element.text.split(), dtype=np.float64)


def read_gismo(path):
    """The curves (``igaparam.Curve``) or surfaces (``igaparam.Surface``) of a G+Smo XML file,
    in file order."""
    out = []
    for geometry in ET.parse(path).getroot().iter("Geometry"):
        kind = geometry.get("type")
        knots = [(int(k.get("degree")), _numbers(k)) for k in geometry.iter("KnotVector")]
        coefs = geometry.find("coefs")
        points = _numbers(coefs).reshape(-1, int(coefs.get("geoDim")))
        weights = geometry.find(".//weights")
        weights = None if weights is None else _numbers(weights)
        if kind in ("BSpline", "Nurbs"):
            (degree, kv), = knots
            out.append(igaparam.Curve(degree, kv, points, weights))
        elif kind in ("TensorBSpline2", "TensorNurbs2"):
            (pu, ku), (pv, kv) = knots
            nu, nv = len(ku) - pu - 1, len(kv) - pv - 1
            grid = points.reshape(nv, nu, 3)
            out.append(igaparam.Surface((pu, pv), (ku, kv), grid, None if weights is None else weights.reshape(nv, nu)))
        else:
            raise ValueError(f"{path}: geometry type {kind} is not a curve or a tensor surface")
    return out


def grown_knob(curves, s):
    """The curves with the knob of the first one scaled by ``1 + 0.2 s`` about (0.07, 0.2)."""
    first = curves[0]
    points = np.array(first.control_points)
    weight = np.zeros(len(points))
    weight[10:26] = 1.0
    weight[[9, 26]] = 0.5
    centre = np.array([0.07, 0.2])
    points = centre + (1 + 0.2 * s * weight)[:, None] * (points - centre)
    return [igaparam.Curve(first.degree, first.knots, points, first.weights)] + list(curves[1:])


def bulged_face(surfaces, s):
    """The surfaces with the inner control points of the last one scaled about their centroid by
    ``1 + 0.1 s w``, ``w = 16 a(1 - a) b(1 - b)`` of the point's place (a, b) in the net."""
    last = surfaces[-1]
    grid = np.array(last.control_points)
    nv, nu = grid.shape[:2]
    a = np.linspace(0, 1, nu)[None, :]
    b = np.linspace(0, 1, nv)[:, None]
    factor = 1 + 0.1 * s * 16 * a * (1 - a) * b * (1 - b)
    centre = grid.reshape(-1, 3).mean(axis=0)
    grid = centre + factor[:, :, None] * (grid - centre)
    return list(surfaces[:-1]) + [igaparam.Surface(last.degree, last.knots, grid, last.weights)]


def run(path, steps=20, threads=0, out=sys.stdout):
    """Runs the loop; returns the summary (also printed as the last line)."""
    shapes = read_gismo(path)
    solid = isinstance(shapes[0], igaparam.Surface)
    morph = bulged_face if solid else grown_knob
    make = igaparam.Domain.solid_from_surfaces if solid else igaparam.Domain.from_curves
    clock = time.perf_counter()
    with make(shapes) as domain:
        domain.build(threads=threads)
        with igaparam.Spline.fit(domain) as spline:
            cold = time.perf_counter() - clock
            basis, elements, levels = spline.basis_count, spline.element_bounds, spline.element_levels
            print(f"{path}: {domain.cell_count} cells, {basis} functions, fit by "
                  f"{spline.fit_rule.name.lower()} ({cold:.2f} s)", file=out)
            print(" step  basis  certified  min q_S  update s  refit s", file=out)
            ok, seconds = True, []
            for step in range(1, steps + 1):
                if solid:
                    domain.set_boundary(surfaces=morph(shapes, step / steps))
                else:
                    domain.set_boundary(curves=morph(shapes, step / steps))
                clock = time.perf_counter()
                update = domain.update(threads=threads)
                middle = time.perf_counter()
                refit = spline.refit(domain)
                seconds.append(time.perf_counter() - clock)
                same = (spline.basis_count == basis and np.array_equal(spline.element_bounds, elements)
                        and np.array_equal(spline.element_levels, levels))
                ok = ok and same and refit.certified_positive and update.domain.invalid_cells == 0
                print(f"{step:5d}  {spline.basis_count:5d}  {str(refit.certified_positive):>9}  "
                      f"{refit.min_quality:7.3f}  {middle - clock:8.3f}  {seconds[-1] - (middle - clock):7.3f}",
                      file=out)
    summary = {
        "steps": steps,
        "basis": basis,
        "elements": len(levels),
        "all_certified_same_space": ok,
        "median_step_seconds": float(np.median(seconds)),
        "cold_build_and_fit_seconds": cold,
    }
    print(json.dumps(summary), file=out)
    return summary


def sensitivity_check(path, h=1e-4, threads=0, out=sys.stdout):
    """Compares dJ/ds by the adjoint with central differences (see the module documentation);
    returns the summary (also printed)."""
    curves = read_gismo(path)
    if isinstance(curves[0], igaparam.Surface):
        raise ValueError("the sensitivity check morphs a planar boundary of four curves")
    # The growth is linear in s: the curves' control points move by morph(1) - morph(0) per unit.
    dc = np.concatenate([np.asarray(g.control_points) - np.asarray(c.control_points)
                         for g, c in zip(grown_knob(curves, 1.0), curves)])
    with igaparam.Domain.from_curves(curves) as domain:
        report = domain.build(threads=threads, boundary_offset=0.0, stationarity_tolerance=1e-12)
        with igaparam.Spline.fit(domain) as spline:
            if spline.fit_report.untangled:
                spline.refit(domain)  # carries the untangling's correction as a constant
            clock = time.perf_counter()
            adjoint = float(np.sum(spline.adjoint_controls(domain, spline.control_points) * dc))
            product = time.perf_counter() - clock
            values = []
            for s in (h, -h):
                domain.set_boundary(curves=grown_knob(curves, s))
                domain.update(threads=threads)
                spline.refit(domain)
                values.append(0.5 * float(np.sum(spline.control_points ** 2)))
    central = (values[0] - values[1]) / (2 * h)
    error = abs(adjoint - central) / abs(central)
    print(f"{path}: gradient norm {report.gradient_norm:.1e} after {report.newton_iterations} "
          f"Newton iterations; dJ/ds adjoint {adjoint:.10e} ({product * 1e3:.1f} ms), "
          f"central differences {central:.10e}, relative difference {error:.1e}", file=out)
    summary = {"adjoint": adjoint, "central": central, "relative_error": error,
               "adjoint_seconds": product}
    print(json.dumps(summary), file=out)
    return summary


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("boundary", help="a G+Smo XML file of four curves or six surfaces")
    parser.add_argument("--steps", type=int, default=20)
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--check-sensitivities", action="store_true",
                        help="check the control-point sensitivities against finite differences")
    args = parser.parse_args()
    if args.check_sensitivities:
        return 0 if sensitivity_check(args.boundary, threads=args.threads)["relative_error"] <= 1e-6 else 1
    summary = run(args.boundary, args.steps, args.threads)
    return 0 if summary["all_certified_same_space"] else 1


if __name__ == "__main__":
    sys.exit(main())
