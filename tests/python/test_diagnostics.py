"""Diagnostics: with IGAPARAM_DEBUG set, a relocation prints its stages on standard error, each
with a time stamp that never goes back, from its start to its end; without it, nothing. Run in a
child process (the variable is read by the library as it goes)."""

import os
import re
import subprocess
import sys

SCRIPT = """
from test_progress_rule import bumped_grid
with bumped_grid() as mesh:
    report = mesh.relocate(method="newton", threads=2)
    assert report.invalid_after == 0
"""


def relocate_with(debug):
    env = dict(os.environ)
    env.pop("IGAPARAM_DEBUG", None)
    if debug:
        env["IGAPARAM_DEBUG"] = "1"
    here = os.path.dirname(os.path.abspath(__file__))
    env["PYTHONPATH"] = os.pathsep.join([here] + [p for p in sys.path if p])
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
    assert messages[0].startswith("relocation: 25 nodes, 16 cells, Newton"), messages
    assert messages[-1].startswith("relocation: done in"), messages
    assert " 0 invalid" in messages[-1], messages
    for stage in ("Hessian layout:", "preconditioner: Cholesky factor", "newton 1 g"):
        assert any(m.startswith(stage) for m in messages), (stage, messages)
    assert relocate_with(False) == ""
