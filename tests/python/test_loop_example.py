"""The shape-optimization example of the Python package (bindings/python/examples) runs, checks
its adjoint gradient against central differences, keeps every relocated mesh valid and converges."""

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "bindings" / "python" / "examples" / "airfoil_optimization.py"


def test_airfoil_optimization_converges_with_a_checked_gradient():
    run = subprocess.run([sys.executable, str(EXAMPLE), "--threads", "2"], capture_output=True, text=True,
                         env=dict(os.environ), timeout=600)
    assert run.returncode == 0, run.stderr
    summary = json.loads(run.stdout.strip().splitlines()[-1])
    assert summary["gradient_check"] < 1e-6, summary
    assert summary["all_valid"], summary
    assert summary["converged"], summary
    assert summary["J_end"] < summary["J_start"], summary
    assert summary["gradient_end"] < 1e-4, summary
