"""MFEM TMOP (PyMFEM) on a relocation case written by `cargo bench --bench relocate`, for the
benchmark's peer column.

    python3 benches/tmop.py CASE.vtu [ITERATIONS]

CASE.vtu is an ASCII .vtu of Q9 cells whose points are the reference positions, with the point
arrays `fixed_components` (3 = fixed), `moved` (the prescribed positions) and `start` (where the
free nodes start: the harmonic placement), and optionally `relocated` (igaparam's result, whose
qualities are then measured here too, a check that both are measured alike). The setup is TMOP's mesh-optimizer miniapp's for a
tangled start: metric 22 (untangling shape, with the worst determinant tracked by the Newton
solver) until no Jacobian at the quadrature points is negative, then metric 2 (shape); target:
each cell's own reference shape (GIVEN_SHAPE_AND_SIZE, the target igaparam relocates to);
Newton with MINRES, Gauss-Lobatto rules of order 8. Prints one line `TMOP key=value ...` with
the seconds, the Newton iterations, the folded cells and the qualities measured as igaparam
measures them (1 / mean over the 3x3 Gauss-Lobatto points of |S|^2 / (2 det S), S = J W^-1,
W the reference Jacobian; 0 for a cell folded at one of them).
"""

import sys
import time
import xml.etree.ElementTree as ET

import numpy as np
import mfem.ser as mfem
import mfem._ser.tmop as tmop
import mfem._ser.tmop_tools as tmop_tools

ORDER = 8


def read_vtu(path):
    root = ET.parse(path).getroot()
    return {a.get("Name"): np.array(a.text.split(), dtype=float) for a in root.iter("DataArray")}


def q9_mesh(reference, cells):
    """An order-2 MFEM mesh of the Q9 cells (VTK order: corners, mid-edges, centre, which is
    MFEM's order of a quadrilateral's dofs) and, per nodal dof, its node."""
    corners = np.unique(cells[:, :4])
    vertex = {int(n): i for i, n in enumerate(corners)}
    mesh = mfem.Mesh(2, len(corners), len(cells), 0, 2)
    for n in corners:
        mesh.AddVertex([float(reference[n, 0]), float(reference[n, 1])])
    for c in cells:
        mesh.AddQuad([vertex[int(n)] for n in c[:4]])
    mesh.FinalizeQuadMesh(1, 0, False)
    mesh.SetCurvature(2, False, 2, mfem.Ordering.byNODES)
    space = mesh.GetNodalFESpace()
    node_of = -np.ones(space.GetNDofs(), dtype=int)
    for e in range(len(cells)):
        for i, d in enumerate(space.GetElementDofs(e)):
            node_of[d if d >= 0 else -1 - d] = cells[e, i]
    assert (node_of >= 0).all()
    return mesh, space, node_of


def set_grid_function(gf, values, node_of):
    n = len(node_of)
    for k in range(2):
        for d in range(n):
            gf[k * n + d] = values[node_of[d], k]


def min_det(mesh, rule):
    worst = np.inf
    for e in range(mesh.GetNE()):
        t = mesh.GetElementTransformation(e)
        for q in range(rule.GetNPoints()):
            t.SetIntPoint(rule.IntPoint(q))
            worst = min(worst, t.Jacobian().Det())
    return worst


def optimize(space, rules, rule, x0, fixed_vdofs, metric_id, iterations, worst):
    """Runs TMOP's Newton solver with metric `metric_id` on the mesh's nodes; returns its
    iteration count. (`rules` must outlive `rule`, which points into it.)"""
    mesh = space.GetMesh()
    keep = []
    if metric_id == 22:
        tau = mfem.doublep()
        tau.assign(worst)
        keep.append(tau)
        metric = tmop.TMOP_Metric_022(tau)
    else:
        metric = tmop.TMOP_Metric_002()
    target = tmop.TargetConstructor(tmop.TargetConstructor.GIVEN_SHAPE_AND_SIZE)
    target.SetNodes(x0)
    integrator = tmop.TMOP_Integrator(metric, target)
    integrator.SetIntegrationRules(rules, ORDER)
    form = mfem.NonlinearForm(space)
    form.AddDomainIntegrator(integrator)
    form.SetEssentialVDofs(fixed_vdofs)
    minres = mfem.MINRESSolver()
    minres.SetMaxIter(100)
    minres.SetRelTol(1e-12)
    minres.SetAbsTol(0.0)
    minres.SetPrintLevel(-1)
    solver = tmop_tools.TMOPNewtonSolver(rule, 0)
    solver.SetIntegrationRules(rules, ORDER)
    solver.SetPreconditioner(minres)
    solver.SetMaxIter(iterations)
    solver.SetRelTol(1e-10)
    solver.SetAbsTol(0.0)
    solver.SetPrintLevel(-1)
    if metric_id == 22:
        detp = mfem.doublep()
        detp.assign(worst)
        keep.append(detp)
        solver.SetMinDetPtr(detp)
    solver.SetOperator(form)
    nodes = mesh.GetNodes()
    nodes.SetTrueVector()
    solver.Mult(mfem.Vector(0), nodes.GetTrueVector())
    nodes.SetFromTrueVector()
    return solver.GetNumIterations()


def lagrange_derivatives():
    """Derivatives of the nine Q9 shape functions (VTK order) at the 3x3 Gauss-Lobatto points."""
    lattice = [(0, 0), (2, 0), (2, 2), (0, 2), (1, 0), (2, 1), (1, 2), (0, 1), (1, 1)]
    t = [-1.0, 0.0, 1.0]
    value = [lambda s: s * (s - 1) / 2, lambda s: 1 - s * s, lambda s: s * (s + 1) / 2]
    slope = [lambda s: s - 0.5, lambda s: -2 * s, lambda s: s + 0.5]
    out = np.zeros((9, 9, 2))
    for q in range(9):
        u, v = t[q % 3], t[q // 3]
        for n, (i, j) in enumerate(lattice):
            out[q, n] = [slope[i](u) * value[j](v), value[i](u) * slope[j](v)]
    return out


def qualities(positions, reference, cells):
    """igaparam's cell quality against the reference shapes."""
    g = lagrange_derivatives()
    out = np.zeros(len(cells))
    for c, nodes in enumerate(cells):
        x, w = positions[nodes], reference[nodes]
        total = 0.0
        for q in range(9):
            s = (x.T @ g[q]) @ np.linalg.inv(w.T @ g[q])
            det = np.linalg.det(s)
            if det <= 0:
                total = np.inf
                break
            total += (s * s).sum() / (2 * det)
        out[c] = 0.0 if not np.isfinite(total) else 9.0 / total
    return out


def main():
    arrays = read_vtu(sys.argv[1])
    iterations = int(sys.argv[2]) if len(sys.argv) > 2 else 500
    reference = arrays["Points"].reshape(-1, 3)[:, :2]
    start = arrays["start"].reshape(-1, 3)[:, :2]
    fixed = arrays["fixed_components"].astype(int) == 3
    cells = arrays["connectivity"].astype(int).reshape(-1, 9)
    mesh, space, node_of = q9_mesh(reference, cells)
    x0 = mfem.GridFunction(space)
    set_grid_function(x0, reference, node_of)
    set_grid_function(mesh.GetNodes(), start, node_of)
    fixed_vdofs = mfem.intArray()
    for k in range(2):
        for d in np.nonzero(fixed[node_of])[0]:
            fixed_vdofs.Append(space.DofToVDof(int(d), k))
    clock = time.perf_counter()
    rules = mfem.IntegrationRules(0, mfem.Quadrature1D.GaussLobatto)
    rule = rules.Get(space.GetFE(0).GetGeomType(), ORDER)
    worst = min_det(mesh, rule)
    done = 0
    if worst <= 0:
        done += optimize(space, rules, rule, x0, fixed_vdofs, 22, iterations, worst)
        worst = min_det(mesh, rule)
    if worst > 0:
        done += optimize(space, rules, rule, x0, fixed_vdofs, 2, iterations, worst)
    seconds = time.perf_counter() - clock
    nodes = mesh.GetNodes()
    n = len(node_of)
    final = start.copy()
    for d in range(n):
        final[node_of[d]] = [nodes[d], nodes[n + d]]
    q = qualities(final, reference, cells)
    folded_at_start = int((qualities(start, reference, cells) <= 0).sum())
    line = (
        f"TMOP start_folded={folded_at_start} seconds={seconds:.3f} iterations={done} folded={int((q <= 0).sum())} "
        f"min_q={q.min():.3f} mean_q={q.mean():.3f}"
    )
    if "relocated" in arrays:
        ours = qualities(arrays["relocated"].reshape(-1, 3)[:, :2], reference, cells)
        line += f" (igaparam's result measured here: min_q={ours.min():.3f} mean_q={ours.mean():.3f})"
    print(line)


if __name__ == "__main__":
    main()
