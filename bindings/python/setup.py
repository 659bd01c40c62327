"""Build hooks of the igaparam Python package: its wheel carries the shared library libigaparam.

- build_py builds the library with cargo (``cargo build --release --lib``, in ``CARGO_TARGET_DIR``
  or the crate's own ``target/``, so an up-to-date build there is reused as it is) and copies it
  into the package; ``IGAPARAM_PREBUILT_LIBRARY=/path/to/libigaparam.so`` bundles an already built
  library instead, without cargo.
- sdist copies the Rust crate (manifest, lock file, sources, header) into ``rust/``, so that the
  source distribution builds on its own.
- bdist_wheel tags the wheel for the platform (``py3-none-<platform>``): it holds native code but
  no Python extension module (the library is loaded with ctypes).
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Distribution, setup
from setuptools.command.bdist_wheel import bdist_wheel
from setuptools.command.build_py import build_py
from setuptools.command.sdist import sdist

HERE = Path(__file__).resolve().parent
# What the crate needs to build (benches: Cargo.toml declares them).
CRATE_ITEMS = ["Cargo.toml", "Cargo.lock", "build.rs", "cbindgen.toml", "README.md", "src", "include", "benches"]


def library_name():
    if sys.platform == "win32":
        return "igaparam.dll"
    if sys.platform == "darwin":
        return "libigaparam.dylib"
    return "libigaparam.so"


def crate_dir():
    """The Rust crate: ``rust/`` in a source distribution, else the checkout two levels up."""
    for candidate in (HERE / "rust", HERE.parent.parent):
        manifest = candidate / "Cargo.toml"
        if manifest.is_file() and 'name = "igaparam"' in manifest.read_text():
            return candidate
    raise RuntimeError(
        "igaparam: the Rust crate is neither in rust/ nor two levels up; build from a checkout "
        "of igaparam or from its source distribution, or set IGAPARAM_PREBUILT_LIBRARY"
    )


def cargo():
    found = shutil.which("cargo") or shutil.which("cargo", path=str(Path.home() / ".cargo" / "bin"))
    if not found:
        raise RuntimeError(
            "igaparam: cargo not found (install Rust, https://rustup.rs), or set "
            "IGAPARAM_PREBUILT_LIBRARY to an already built libigaparam"
        )
    return found


def built_library():
    """The path of the library to bundle: IGAPARAM_PREBUILT_LIBRARY, or cargo's build."""
    prebuilt = os.environ.get("IGAPARAM_PREBUILT_LIBRARY")
    if prebuilt:
        if not Path(prebuilt).is_file():
            raise RuntimeError(f"igaparam: IGAPARAM_PREBUILT_LIBRARY={prebuilt} is not a file")
        return Path(prebuilt)
    crate = crate_dir()
    target = Path(os.environ.get("CARGO_TARGET_DIR") or crate / "target")
    command = [cargo(), "build", "--release", "--lib", "--manifest-path", str(crate / "Cargo.toml")]
    print("igaparam: " + " ".join(command), file=sys.stderr, flush=True)
    subprocess.run(command, check=True, env=dict(os.environ, CARGO_TARGET_DIR=str(target)))
    return target / "release" / library_name()


class BuildWithLibrary(build_py):
    """build_py that also puts the shared library into the package."""

    def run(self):
        super().run()
        library = built_library()
        destination = Path(self.build_lib) / "igaparam" / library_name()
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(library, destination)


class SdistWithCrate(sdist):
    """sdist that carries the Rust crate in rust/."""

    def make_release_tree(self, base_dir, files):
        super().make_release_tree(base_dir, files)
        crate = crate_dir()
        target = Path(base_dir) / "rust"
        for item in CRATE_ITEMS:
            source = crate / item
            if source.is_dir():
                shutil.copytree(source, target / item, ignore=shutil.ignore_patterns("__pycache__"))
            elif source.is_file():
                target.mkdir(parents=True, exist_ok=True)
                shutil.copyfile(source, target / item)


class BinaryDistribution(Distribution):
    """A distribution with native code (the shared library), built per platform."""

    def has_ext_modules(self):
        return True


class PlatformWheel(bdist_wheel):
    """A wheel for this platform, for any Python 3 (ctypes, no extension module)."""

    def get_tag(self):
        return ("py3", "none", super().get_tag()[2])


setup(
    distclass=BinaryDistribution,
    cmdclass={"build_py": BuildWithLibrary, "sdist": SdistWithCrate, "bdist_wheel": PlatformWheel},
)
