"""The Python examples of README.md and docs/loops.md, extracted and run, and the links of
README.md and docs/*.md checked (see tests/readme/)."""

import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("readme_examples", ROOT / "tests" / "readme" / "readme_examples.py")
readme_examples = importlib.util.module_from_spec(spec)
spec.loader.exec_module(readme_examples)


def test_readme_python_example(tmp_path):
    pytest.importorskip("meshio")
    code = readme_examples.examples()["python"]
    work = readme_examples.work_directory(tmp_path / "python")
    (work / "example.py").write_text(code)
    run = subprocess.run([sys.executable, "example.py"], cwd=work, capture_output=True, text=True, env=os.environ)
    assert run.returncode == 0, run.stderr
    assert "airfoil: 63 folded cells before, 0 after" in run.stdout
    assert re.search(r"^puzzle: \d+ cells, 0 invalid", run.stdout, re.MULTILINE), run.stdout
    # The file written, read back: the 490 Q9 cells, no folded one left (the positions are not
    # the input's: the profile moved).
    meshio = pytest.importorskip("meshio")
    written = meshio.read(work / "airfoil_relocated.vtu")
    cells = written.cells_dict["quad9"]
    assert cells.shape == (490, 9) and written.points.shape == (2060, 3)
    original = meshio.read(readme_examples.ROOT / "tests" / "data" / "airfoil_0012_q9.vtu")
    assert np.array_equal(cells, original.cells_dict["quad9"])
    assert not np.allclose(written.points, original.points)
    quality = np.asarray(written.cell_data["quality"][0])
    assert quality.shape == (490,) and quality.min() > 0 and quality.max() <= 1


def test_readme_loop_example(tmp_path):
    code = readme_examples.examples()["pyloop"]
    work = readme_examples.work_directory(tmp_path / "pyloop")
    (work / "example.py").write_text(code)
    run = subprocess.run([sys.executable, "example.py"], cwd=work, capture_output=True, text=True, env=os.environ)
    assert run.returncode == 0, run.stderr
    assert re.search(r"^60 degrees in 20 warm steps: quality min 0\.6\d\d", run.stdout, re.MULTILINE), run.stdout


def test_readme_markers():
    found = readme_examples.examples()
    assert set(found) == {"c", "cloop", "cpp", "cmake", "python", "pyloop"}
    with pytest.raises(ValueError):
        readme_examples.examples("<!-- example: c -->\nno block\n")


def test_readme_and_docs_links_resolve():
    broken = readme_examples.broken_links()
    assert not broken, "broken links:\n" + "\n".join(broken)


def test_link_check_finds_broken_links(tmp_path):
    (tmp_path / "there.md").write_text("# A heading\n")
    page = tmp_path / "page.md"
    page.write_text(
        "[ok](there.md) [ok](there.md#a-heading) [ok](#top) [web](https://example.org/x)\n"
        "# Top\n"
        "[gone](missing.md) ![gone](missing.png) [bad anchor](there.md#no-such) `[code](skipped.md)`\n"
        "```\n[fenced](skipped.md)\n```\n"
    )
    broken = readme_examples.broken_links([page])
    assert [b.split(": ", 1)[1] for b in broken] == [
        "missing.md (no such file)", "missing.png (no such file)", "there.md#no-such (no such heading)"]
