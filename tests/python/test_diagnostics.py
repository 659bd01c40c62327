"""Diagnostics: with IGAPARAM_DEBUG set, a relocation prints its stages on standard error, each
with a time stamp that never goes back, from its start to its end; without it, nothing. Run in a
child process (the variable is read by the library as it goes)."""

import os
import re
import subprocess
import sys

SCRIPT = """
import numpy as np
from igaparam import Mesh
n = 6
x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
points = np.column_stack([x.ravel(), y.ravel(), np.zeros(n * n)])
cells = [[j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i]
         for j in range(n - 1) for i in range(n - 1)]
with Mesh("Q4", points, np.array(cells)) as mesh:
    boundary = (points[:, 0] % 1 == 0) | (points[:, 1] % 1 == 0)
    mesh.set_fixed(np.where(boundary, 3, 0).astype(np.uint8))
    top = np.flatnonzero(points[:, 1] == 1)
    moved = points[top].copy()
    moved[:, 1] += 0.2 * np.sin(np.pi * moved[:, 0])
    mesh.move_nodes(moved, indices=top)
    report = mesh.relocate(method="newton", threads=2)
    assert report.invalid_after == 0
"""


def relocate_with(debug):
    env = dict(os.environ)
    env.pop("IGAPARAM_DEBUG", None)
    if debug:
        env["IGAPARAM_DEBUG"] = "1"
    env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)
    done = subprocess.run([sys.executable, "-c", SCRIPT], env=env, capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stderr


def test_stages_are_printed_with_time_stamps_only_when_asked():
    lines = relocate_with(True).splitlines()
    stamped = [re.match(r"\[\s*(\d+\.\d{3}) s\] (.*)", line) for line in lines]
    assert lines and all(stamped), lines
    seconds = [float(m.group(1)) for m in stamped]
    assert seconds == sorted(seconds), lines
    messages = [m.group(2) for m in stamped]
    assert messages[0].startswith("relocation: 36 nodes, 25 cells, Newton"), messages
    assert messages[-1].startswith("relocation: done in"), messages
    assert " 0 invalid" in messages[-1], messages
    for stage in ("Hessian layout:", "preconditioner: Cholesky factor", "newton 1 g"):
        assert any(m.startswith(stage) for m in messages), (stage, messages)
    assert relocate_with(False) == ""
