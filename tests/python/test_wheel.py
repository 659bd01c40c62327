"""The Python package as a user installs it: `pip install bindings/python` into a brand-new
virtual environment gives a package that carries libigaparam and works with no environment
variable; its wheel is tagged for the platform and its sdist carries the Rust crate.

The install builds the library with cargo in the crate's target directory, where the test
suite's own build (cargo test --release) is reused, so it takes seconds."""

import os
import subprocess
import sys
import tarfile
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "bindings" / "python"


def clean_env():
    """The environment without any IGAPARAM_ variable (the library must come with the package)."""
    return {k: v for k, v in os.environ.items() if not k.startswith("IGAPARAM_")}


def run(*command, cwd=None, env=None):
    result = subprocess.run([str(c) for c in command], cwd=cwd, env=env or clean_env(),
                            capture_output=True, text=True)
    assert result.returncode == 0, f"{command} failed:\n{result.stdout}\n{result.stderr}"
    return result.stdout


def test_pip_install_into_a_new_venv_carries_the_library(tmp_path):
    venv = tmp_path / "venv"
    run(sys.executable, "-m", "venv", venv)
    python = venv / "bin" / "python"
    run(python, "-m", "pip", "install", "-q", PACKAGE)
    out = run(python, "-c", "import igaparam, os; print(igaparam.version()); print(os.path.dirname(igaparam.__file__))",
              cwd=tmp_path)
    version, location = out.split()
    assert version == "0.1.0"
    installed = Path(location)
    assert installed.is_relative_to(venv) and (installed / "libigaparam.so").is_file()
    assert (installed / "py.typed").is_file()
    # A relocation through the bundled library.
    code = ("import igaparam, numpy as np\n"
            "p = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)\n"
            "with igaparam.Mesh('quad', p, [[0, 1, 2, 3]]) as m:\n"
            "    print(m.relocate().invalid_after)\n")
    assert run(python, "-c", code, cwd=tmp_path).strip() == "0"
    # IGAPARAM_LIBRARY stays an override: a wrong path is reported, not replaced.
    env = dict(clean_env(), IGAPARAM_LIBRARY=str(tmp_path / "missing.so"))
    result = subprocess.run([str(python), "-c", "import igaparam; igaparam.version()"], cwd=tmp_path, env=env,
                            capture_output=True, text=True)
    assert result.returncode != 0 and "IGAPARAM_LIBRARY" in result.stderr

    # The wheel is for this platform and holds the library; the sdist holds the crate.
    dist = tmp_path / "dist"
    run(python, "-m", "pip", "wheel", "-q", "--no-deps", "-w", dist, PACKAGE)
    (wheel,) = dist.glob("*.whl")
    assert wheel.name.startswith("igaparam-0.1.0-py3-none-") and not wheel.name.endswith("-any.whl")
    assert {"igaparam/libigaparam.so", "igaparam/py.typed"} <= set(zipfile.ZipFile(wheel).namelist())
    run(python, "-m", "pip", "install", "-q", "build")
    run(python, "-m", "build", "--sdist", "--outdir", dist, PACKAGE)
    (sdist,) = dist.glob("*.tar.gz")
    names = set(tarfile.open(sdist).getnames())
    for item in ("setup.py", "rust/Cargo.toml", "rust/Cargo.lock", "rust/src/lib.rs", "rust/include/igaparam.h"):
        assert f"igaparam-0.1.0/{item}" in names, item
