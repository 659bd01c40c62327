"""The generated declarations (igaparam/_ffi.py) against the C header they come from.

A C compiler reads the header and prints the size and field offsets of every struct and the
value of every constant and enum member; the ctypes declarations must agree to the byte. The
generator must notice a changed field, and the loader must refuse a library built from other
declarations.
"""

import ctypes
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from igaparam import _capi, _ffi

ROOT = Path(__file__).resolve().parents[2]
HEADER = ROOT / "include" / "igaparam.h"
sys.path.insert(0, str(ROOT / "bindings" / "python"))
import gen_ffi  # noqa: E402

STRUCTS = [
    (name, value)
    for name, value in vars(_ffi).items()
    if isinstance(value, type) and issubclass(value, ctypes.Structure) and value is not ctypes.Structure
]
ENUMS = [value for value in vars(_ffi).values() if isinstance(value, type) and issubclass(value, _ffi.enum.IntEnum)]
CONSTANTS = {
    name: value for name, value in vars(_ffi).items() if name.isupper() and isinstance(value, (int, float))
}


def c_name(struct):
    return re.search(r"\(``(\w+)``\)", struct.__doc__).group(1)


def c_facts(tmp_path):
    """{key: value} printed by a C program compiled against the header."""
    compiler = shutil.which(os.environ.get("CC", "cc")) or shutil.which("gcc")
    if compiler is None:
        pytest.skip("no C compiler")
    lines = ['#include <stdio.h>', '#include <stddef.h>', '#include "igaparam.h"', "int main(void) {"]
    for _, struct in STRUCTS:
        name = c_name(struct)
        lines.append(f'printf("sizeof {name} %zu\\n", sizeof({name}));')
        for field, _ in struct._fields_:
            lines.append(f'printf("offsetof {name}.{field} %zu\\n", offsetof({name}, {field}));')
    for name, value in CONSTANTS.items():
        if name != "ABI_FINGERPRINT":
            form, cast = ("%.17g", "double") if isinstance(value, float) else ("%lld", "long long")
            lines.append(f'printf("value {name} {form}\\n", ({cast})IGAPARAM_{name});')
    for enum in ENUMS:
        prefix = re.search(r"\(``igaparam_(\w+)``\)", enum.__doc__).group(1).upper()
        if prefix == "FIT_RULE":
            prefix = "FIT"
        for member in enum:
            lines.append(f'printf("enum {enum.__name__}.{member.name} %d\\n", (int)IGAPARAM_{prefix}_{member.name});')
    lines += ["return 0;", "}"]
    source = tmp_path / "facts.c"
    source.write_text("\n".join(lines))
    program = tmp_path / "facts"
    subprocess.run([compiler, "-std=c11", "-I", str(ROOT / "include"), str(source), "-o", str(program)], check=True)
    out = subprocess.run([str(program)], check=True, capture_output=True, text=True).stdout
    return dict(line.rsplit(" ", 1) for line in out.splitlines())


def test_layouts_constants_and_enums_match_the_compiler(tmp_path):
    facts = c_facts(tmp_path)
    assert len(STRUCTS) >= 15 and len(ENUMS) >= 3
    for _, struct in STRUCTS:
        name = c_name(struct)
        assert int(facts[f"sizeof {name}"]) == ctypes.sizeof(struct), name
        for field, _ in struct._fields_:
            offset = getattr(struct, field).offset
            assert int(facts[f"offsetof {name}.{field}"]) == offset, f"{name}.{field}"
    for name, value in CONSTANTS.items():
        if name != "ABI_FINGERPRINT":
            assert float(facts[f"value {name}"]) == value, name
    for enum in ENUMS:
        for member in enum:
            assert int(facts[f"enum {enum.__name__}.{member.name}"]) == int(member), member


def test_every_function_of_the_header_is_declared():
    declared = set(re.findall(r"\b(igaparam_\w+)\(", re.sub(r"/\*.*?\*/", "", HEADER.read_text(), flags=re.S)))
    assert declared == set(_ffi.PROTOTYPES)
    library = _capi.library()
    for name, (restype, argtypes, doc) in _ffi.PROTOTYPES.items():
        function = getattr(library, name)
        assert function.argtypes == argtypes and function.restype == restype, name
        assert function.__doc__ == doc and name in doc


def test_the_checked_in_module_is_what_the_header_generates():
    assert gen_ffi.generate(HEADER.read_text(encoding="utf-8")) == (ROOT / "bindings/python/igaparam/_ffi.py").read_text(
        encoding="utf-8"
    )


def test_a_changed_field_changes_the_declarations_and_the_fingerprint():
    text = HEADER.read_text(encoding="utf-8")
    changed = text.replace("  uint32_t max_sweeps;\n", "  double max_sweeps;\n", 1)
    assert changed != text
    before, after = gen_ffi.generate(text), gen_ffi.generate(changed)
    assert before != after
    assert gen_ffi.fingerprint(text) != gen_ffi.fingerprint(changed)
    # Comments alone do not change the fingerprint.
    assert gen_ffi.fingerprint(text) == gen_ffi.fingerprint(text.replace("Success.", "Success!"))


def test_an_unknown_shape_is_an_error_naming_its_line():
    text = HEADER.read_text(encoding="utf-8").replace("typedef struct {", "typedef union {", 1)
    with pytest.raises(gen_ffi.HeaderError, match=r"line \d+"):
        gen_ffi.generate(text)


def test_a_library_of_other_declarations_is_refused(monkeypatch):
    library = _capi.library()
    assert library.igaparam_abi_fingerprint() == _ffi.ABI_FINGERPRINT
    monkeypatch.setattr(_ffi, "ABI_FINGERPRINT", _ffi.ABI_FINGERPRINT ^ 1)
    path = os.environ.get("IGAPARAM_LIBRARY") or library._name
    monkeypatch.setenv("IGAPARAM_LIBRARY", path)
    with pytest.raises(OSError, match="other C declarations"):
        _capi.load_library()
