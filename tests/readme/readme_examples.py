"""The code examples of README.md and of the docs/ pages, extracted and run, so that the
documentation cannot go stale; and the check that their relative links resolve.

An example is a fenced code block right after a marker line ``<!-- example: NAME -->``, in
README.md or a docs/*.md page (names are unique across all of them); NAME is one of ``c`` and
``cloop`` (C programs; cloop is in docs/loops.md), ``cpp``, ``cmake`` (a CMakeLists.txt building
the ``c`` example as ``main.c``), ``python`` and ``pyloop`` (docs/loops.md). Examples run in a
work directory holding a link ``tests`` to the repository's ``tests`` directory, so they read the
bundled data by the paths the pages show.

    python3 readme_examples.py --build-dir BUILD --work-dir DIR NAME...   # c, cpp, cmake

Each compiled example's output is checked (check_output: the figures it prints and, for c and
cmake, the T-mesh file it writes, read back), not only its exit code. The Python example is run
by tests/python/test_readme.py (it needs the virtual environment), which also runs
broken_links(): every relative link and image of these pages must name an existing file, and
every #anchor a heading of its page.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
DOCS = ROOT / "docs"
MARKER = re.compile(r"^<!-- example: ([a-z+]+) -->\s*$")
FENCE = re.compile(r"^```")


def pages():
    """The pages whose examples and links are checked: README.md, then docs/*.md."""
    return [README, *sorted(DOCS.glob("*.md"))]


def examples(text=None, source="README.md"):
    """{name: code} of the marked blocks of `text`, or of README.md and every docs/ page when
    `text` is None (a name given twice, in one page or in two, is an error)."""
    if text is None:
        found = {}
        for page in pages():
            name = page.relative_to(ROOT).as_posix()
            for key, code in examples(page.read_text(encoding="utf-8"), name).items():
                if key in found:
                    raise ValueError(f"{name}: an example named `{key}` is already in another page")
                found[key] = code
        return found
    lines = text.splitlines()
    found = {}
    for i, line in enumerate(lines):
        match = MARKER.match(line)
        if not match:
            continue
        start = i + 1
        if start >= len(lines) or not FENCE.match(lines[start]):
            raise ValueError(f"{source} line {i + 1}: marker `{match.group(1)}` not followed by a ``` block")
        end = next((k for k in range(start + 1, len(lines)) if FENCE.match(lines[k])), None)
        if end is None:
            raise ValueError(f"{source} line {start + 1}: unterminated ``` block")
        name = match.group(1)
        if name in found:
            raise ValueError(f"{source}: two examples named `{name}`")
        found[name] = "\n".join(lines[start + 1 : end]) + "\n"
    return found


LINK = re.compile(r"!?\[[^\]]*\]\(([^()\s]+)\)")
CODE_SPAN = re.compile(r"`[^`]*`")


def prose_lines(text):
    """(line number, line) of `text` outside fenced code blocks, with inline code removed."""
    inside = False
    for number, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            inside = not inside
        elif not inside:
            yield number, CODE_SPAN.sub("", line)


def anchors(text):
    """The #anchors of a page's headings, as GitHub makes them (lower case, punctuation dropped,
    spaces to hyphens, -1, -2, ... for repeats)."""
    seen = {}
    for _, line in prose_lines(text.replace("`", "")):
        heading = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if heading:
            slug = re.sub(r"[^\w\- ]", "", heading.group(1).lower()).replace(" ", "-")
            count = seen.get(slug, 0)
            seen[slug] = count + 1
            yield slug if count == 0 else f"{slug}-{count}"


def broken_links(files=None):
    """["page:line: target (why)", ...] for every relative link or image of the pages (README.md
    and docs/*.md unless `files` is given) that names no existing file, or an #anchor that is no
    heading of its target page."""
    broken = []
    for page in files or pages():
        text = page.read_text(encoding="utf-8")
        for number, line in prose_lines(text):
            for target in LINK.findall(line):
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                    continue
                path, _, anchor = target.partition("#")
                resolved = (page.parent / path).resolve() if path else page
                name = page.relative_to(ROOT).as_posix() if page.is_relative_to(ROOT) else str(page)
                where = f"{name}:{number}: {target}"
                if not resolved.exists():
                    broken.append(f"{where} (no such file)")
                elif anchor and resolved.suffix == ".md" and \
                        anchor not in set(anchors(resolved.read_text(encoding="utf-8"))):
                    broken.append(f"{where} (no such heading)")
    return broken


def work_directory(path):
    """A fresh directory with the link ``tests`` -> the repository's tests/."""
    path = Path(path)
    if path.exists():
        shutil.rmtree(path)
    path.mkdir(parents=True)
    (path / "tests").symlink_to(ROOT / "tests", target_is_directory=True)
    return path


def run(command, cwd, env=None):
    print("+", " ".join(str(c) for c in command), flush=True)
    result = subprocess.run([str(c) for c in command], cwd=cwd, env=env, text=True, capture_output=True)
    sys.stdout.write(result.stdout)
    sys.stderr.write(result.stderr)
    if result.returncode != 0:
        raise SystemExit(f"readme_examples: `{command[0]}` exited with {result.returncode}")
    return result.stdout


def run_compiled(name, code, args, work):
    """Compiles a C (c, cloop) or the cpp example against the build's library and runs it."""
    library = Path(args.build_dir) / "cargo" / "release"
    c = name != "cpp"
    source = work / ("main.c" if c else "main.cpp")
    source.write_text(code)
    compiler = args.c_compiler if c else args.cxx_compiler
    flags = ["-std=c11"] if c else ["-std=c++17", f"-I{ROOT / 'bindings' / 'cpp'}"]
    exe = work / name
    run([compiler, *flags, "-Wall", "-Wextra", "-Werror", f"-I{ROOT / 'include'}", source, "-o", exe,
         f"-L{library}", "-ligaparam", f"-Wl,-rpath,{library}", "-lm"], work)
    return run([exe], work)


def run_cmake(code, c_code, args, work):
    """Installs the build into work/prefix, then configures, builds and runs the cmake example
    (with the c example as main.c) against it."""
    prefix = work / "prefix"
    run([args.cmake, "--install", args.build_dir, "--prefix", prefix], work)
    project = work / "project"
    project.mkdir()
    (project / "CMakeLists.txt").write_text(code)
    (project / "main.c").write_text(c_code)
    build = work / "project-build"
    run([args.cmake, "-S", project, "-B", build, f"-DCMAKE_PREFIX_PATH={prefix}",
         f"-DCMAKE_C_COMPILER={args.c_compiler}", "-DCMAKE_BUILD_TYPE=Release"], work)
    run([args.cmake, "--build", build], work)
    executables = [p for p in build.iterdir() if p.is_file() and os.access(p, os.X_OK)]
    if len(executables) != 1:
        raise SystemExit(f"readme_examples: expected one program in {build}, found {executables}")
    return run([executables[0]], work)


def check_output(name, stdout, work):
    """What each compiled example must print and write, beyond exiting 0 (raises SystemExit)."""
    def fail(what):
        raise SystemExit(f"readme_examples: `{name}` example: {what}\n{stdout}")

    if name in ("c", "cmake"):
        m = re.fullmatch(r"(\d+) cells, (\d+) invalid, quality min ([\d.]+), mean ([\d.]+)\n", stdout)
        if not m or int(m.group(2)) != 0 or not 0 < float(m.group(3)) <= float(m.group(4)) <= 1:
            fail("expected `N cells, 0 invalid, quality min A, mean B` with 0 < A <= B <= 1")
        # The T-mesh file read back: its cell count is the printed one, its arrays are there.
        import xml.etree.ElementTree as ET
        root = ET.parse(work / "puzzle_tmesh.vtu").getroot()
        piece = root.find("UnstructuredGrid/Piece")
        names = {a.get("Name") for a in root.iter("DataArray")}
        if piece is None or int(piece.get("NumberOfCells")) != int(m.group(1)):
            fail("puzzle_tmesh.vtu does not hold the printed number of cells")
        if not {"parametric", "quality", "level"} <= names:
            fail(f"puzzle_tmesh.vtu has the arrays {sorted(n for n in names if n)}")
    elif name == "cpp":
        m = re.fullmatch(r"(\d+) folded cells before, 0 after; quality min ([\d.eE+-]+)\n", stdout)
        if not m or int(m.group(1)) == 0 or not 0 < float(m.group(2)) <= 1:
            fail("expected `K folded cells before, 0 after; quality min Q` with K > 0, 0 < Q <= 1")
    elif name == "cloop":
        steps = re.findall(r"^step +(\d+): a ([\d.]+), \d+ Newton iterations, min quality ([\d.]+), "
                           r"dJ/da (-?[\d.]+), central differences (-?[\d.]+)$", stdout, re.M)
        if [int(s[0]) for s in steps] != list(range(1, 11)):
            fail("expected the lines of steps 1 to 10")
        for _, _, quality, adjoint, fd in steps:
            if not (0 < float(quality) <= 1 and abs(float(adjoint) - float(fd)) <= 1e-6 * abs(float(fd))):
                fail("a step's quality or adjoint derivative is off")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", required=True)
    parser.add_argument("--work-dir", required=True)
    parser.add_argument("--c-compiler", default="cc")
    parser.add_argument("--cxx-compiler", default="c++")
    parser.add_argument("--cmake", default="cmake")
    parser.add_argument("names", nargs="+", choices=["c", "cloop", "cpp", "cmake"])
    args = parser.parse_args()
    args.build_dir = str(Path(args.build_dir).resolve())
    found = examples()
    for name in args.names:
        if name not in found or (name == "cmake" and "c" not in found):
            raise SystemExit(f"readme_examples: README.md and docs/*.md have no `<!-- example: {name} -->` block")
        work = work_directory(Path(args.work_dir) / name)
        if name == "cmake":
            stdout = run_cmake(found["cmake"], found["c"], args, work)
        else:
            stdout = run_compiled(name, found[name], args, work)
        check_output(name, stdout, work)
        print(f"readme_examples: `{name}` example ran", flush=True)


if __name__ == "__main__":
    main()
