"""Gradient-based shape optimization on a Q9 mesh that is relocated, never remeshed.

The design is the bundled NACA 0012 airfoil's angle and four Hicks–Henne bumps of its surface
(two on each side). The objective is computed on the relocated mesh by quadrature,

    J(x) = ∫_Ω g(X) dX + (α/2) |d|²,   g(X) = exp(−|X − c|²/σ²),

the fluid area weighted by a Gaussian below the airfoil's aft part (the airfoil is pushed to cover
it) plus a penalty on the design d. Every evaluation moves the airfoil's nodes, relocates the mesh
warm (placement='incremental') to a stationary point of its quality objective, differentiates J
with respect to every node (dJ/dx by quadrature, written out below), carries that through the
relocation with Mesh.adjoint to the prescribed nodes, and chains it to the design variables.
scipy's L-BFGS-B minimises J.

    python airfoil_optimization.py [--mesh airfoil_0012_q9.vtu] [--threads 2] [--iterations 30]

Prints the gradient check against central differences, one line per evaluation (J, gradient
norm, validity, relocation and adjoint times) and, last, one JSON object.
"""

import argparse
import json
import time
from pathlib import Path

import numpy as np
from scipy.optimize import minimize

import igaparam

ROOT = Path(__file__).resolve().parents[3]
CENTRE = np.array([0.15, -0.12])
SIGMA = 0.1
ALPHA = 10.0
# Hicks–Henne bumps: (peak position along the chord, side: +1 upper, −1 lower).
BUMPS = [(0.3, 1.0), (0.7, 1.0), (0.3, -1.0), (0.7, -1.0)]


def lagrange(t):
    """The 1D quadratic Lagrange basis at −1, 0, 1 and its derivative, at points t."""
    values = np.stack([0.5 * t * (t - 1), 1 - t * t, 0.5 * t * (t + 1)], axis=-1)
    derivatives = np.stack([t - 0.5, -2 * t, t + 0.5], axis=-1)
    return values, derivatives


def q9_basis():
    """Shape functions (9 points × 9 nodes) and their gradients (9 × 9 × 2) at the 3×3 Gauss
    points, nodes in VTK's Q9 order, with the Gauss weights."""
    g = np.sqrt(0.6)
    t = np.array([-g, 0.0, g])
    w = np.array([5.0, 8.0, 5.0]) / 9.0
    # VTK Q9 node order as (i, j) indices of the 1D basis at −1, 0, 1.
    nodes = [(0, 0), (2, 0), (2, 2), (0, 2), (1, 0), (2, 1), (1, 2), (0, 1), (1, 1)]
    value, derivative = lagrange(t)
    n = np.zeros((9, 9))
    dn = np.zeros((9, 9, 2))
    weights = np.zeros(9)
    for q, (a, b) in enumerate((a, b) for b in range(3) for a in range(3)):
        weights[q] = w[a] * w[b]
        for r, (i, j) in enumerate(nodes):
            n[q, r] = value[a, i] * value[b, j]
            dn[q, r] = (derivative[a, i] * value[b, j], value[a, i] * derivative[b, j])
    return n, dn, weights


N, DN, WEIGHTS = q9_basis()


def objective_of_mesh(points, cells):
    """∫_Ω g dX over the Q9 cells and its derivative with respect to every node (n × 3)."""
    x = points[cells][:, :, :2]  # cells × 9 × 2
    position = np.einsum("qr,crk->cqk", N, x)
    jacobian = np.einsum("crk,qrl->cqkl", x, DN)  # ∂X_k/∂ξ_l
    det = jacobian[..., 0, 0] * jacobian[..., 1, 1] - jacobian[..., 0, 1] * jacobian[..., 1, 0]
    offset = position - CENTRE
    g = np.exp(-np.sum(offset * offset, axis=-1) / SIGMA**2)
    value = np.sum(g * det * WEIGHTS)
    # d(g det)/dx_r = ∇g N_r det + g cof(J) ∇N_r, cof(J) = [[J11, −J10], [−J01, J00]].
    grad_g = -2.0 * offset / SIGMA**2 * g[..., None]
    cof = np.stack(
        [np.stack([jacobian[..., 1, 1], -jacobian[..., 1, 0]], -1),
         np.stack([-jacobian[..., 0, 1], jacobian[..., 0, 0]], -1)], -2)
    local = np.einsum("cqk,qr,cq->crk", grad_g, N, det * WEIGHTS)
    local += np.einsum("cq,cqkl,qrl->crk", g * WEIGHTS, cof, DN)
    gradient = np.zeros((points.shape[0], 3))
    np.add.at(gradient[:, :2], cells, local)
    return value, gradient


class Airfoil:
    """The mesh, the airfoil's nodes, and the map from the design to their positions."""

    def __init__(self, path, threads):
        self.mesh = igaparam.Mesh.read_vtu(path)
        self.threads = threads
        self.reference = self.mesh.reference
        prescribed = self.mesh.fixed != 0
        near = np.max(np.abs(self.reference[:, :2]), axis=1) < 1.9
        self.surface = np.flatnonzero(prescribed & near)
        # Start from the reference shape (the file's own motion is not the design's).
        self.mesh.move_nodes(self.reference)
        self.mesh.relocate(threads=threads, stationarity_tolerance=1e-12)
        x0 = self.reference[self.surface]
        chord = np.clip(x0[:, 0] + 0.5, 0.0, 1.0)
        side = np.where(x0[:, 1] >= 0, 1.0, -1.0)
        self.base = x0
        self.shapes = np.stack(
            [np.where(side == s, np.sin(np.pi * chord ** (np.log(0.5) / np.log(p))) ** 3, 0.0) * s
             for p, s in BUMPS], axis=1)  # surface nodes × bumps: the y offset per unit amplitude

    def surface_positions(self, design):
        """Positions of the airfoil's nodes for design (angle, bumps), and their derivatives."""
        angle, bumps = design[0], design[1:]
        shaped = self.base.copy()
        shaped[:, 1] += self.shapes @ bumps
        c, s = np.cos(angle), np.sin(angle)
        rotation = np.array([[c, -s], [s, c]])
        d_rotation = np.array([[-s, -c], [c, -s]])
        positions = shaped.copy()
        positions[:, :2] = shaped[:, :2] @ rotation.T
        derivative = np.zeros((len(self.surface), 3, len(design)))
        derivative[:, :2, 0] = shaped[:, :2] @ d_rotation.T
        derivative[:, :2, 1:] = rotation[:, 1][None, :, None] * self.shapes[:, None, :]
        return positions, derivative

    def evaluate(self, design):
        """J and dJ/d(design) through a warm relocation and the adjoint."""
        positions, derivative = self.surface_positions(design)
        self.mesh.move_nodes(positions, indices=self.surface)
        start = time.perf_counter()
        report = self.mesh.relocate(threads=self.threads, placement="incremental",
                                    stationarity_tolerance=1e-12)
        relocation = time.perf_counter() - start
        value, dj_dx = objective_of_mesh(self.mesh.positions, self.mesh.cells)
        start = time.perf_counter()
        total = self.mesh.adjoint(dj_dx)
        adjoint = time.perf_counter() - start
        gradient = np.einsum("pk,pkd->d", total[self.surface], derivative)
        value += 0.5 * ALPHA * design @ design
        gradient += ALPHA * design
        return value, gradient, report, relocation, adjoint


def gradient_check(airfoil, design, h=1e-6):
    """Largest relative difference between the adjoint gradient and central differences."""
    _, gradient, *_ = airfoil.evaluate(design)
    fd = np.zeros_like(design)
    for i in range(len(design)):
        step = np.zeros_like(design)
        step[i] = h
        fd[i] = (airfoil.evaluate(design + step)[0] - airfoil.evaluate(design - step)[0]) / (2 * h)
    airfoil.evaluate(design)
    return float(np.max(np.abs(fd - gradient)) / np.max(np.abs(gradient))), gradient, fd


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--mesh", default=str(ROOT / "tests" / "data" / "airfoil_0012_q9.vtu"))
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--iterations", type=int, default=30)
    args = parser.parse_args()
    airfoil = Airfoil(args.mesh, args.threads)
    start_design = np.array([0.02, 0.005, -0.005, 0.005, -0.005])
    error, gradient, fd = gradient_check(airfoil, start_design)
    print(f"gradient check at the start: largest relative difference {error:.2e}")
    for name, a, f in zip(["angle"] + [f"bump {i}" for i in range(len(BUMPS))], gradient, fd):
        print(f"  {name:8s} adjoint {a:+.10e}   central differences {f:+.10e}")
    log = []

    def fun(design):
        value, grad, report, relocation, adjoint = airfoil.evaluate(design)
        log.append({"J": value, "gradient": float(np.linalg.norm(grad)), "invalid": report.invalid_after,
                    "relocation_s": relocation, "adjoint_s": adjoint})
        print(f"{len(log):3d}  J {value:.10f}  |dJ/dd| {np.linalg.norm(grad):.3e}  invalid {report.invalid_after}"
              f"  relocation {1e3 * relocation:6.1f} ms  adjoint {1e3 * adjoint:5.1f} ms")
        return value, grad

    result = minimize(fun, start_design, jac=True, method="L-BFGS-B",
                      options={"maxiter": args.iterations, "gtol": 1e-9})
    summary = {
        "converged": bool(result.success),
        "iterations": int(result.nit),
        "evaluations": len(log),
        "J_start": log[0]["J"],
        "J_end": float(result.fun),
        "gradient_end": float(np.linalg.norm(result.jac)),
        "design": [float(v) for v in result.x],
        "gradient_check": error,
        "all_valid": all(entry["invalid"] == 0 for entry in log),
        "median_relocation_s": float(np.median([e["relocation_s"] for e in log])),
        "median_adjoint_s": float(np.median([e["adjoint_s"] for e in log])),
    }
    print(json.dumps(summary))


if __name__ == "__main__":
    main()
