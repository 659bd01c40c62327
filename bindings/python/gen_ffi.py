#!/usr/bin/env python3
"""Generates ``igaparam/_ffi.py``, the ctypes declarations of the C API, from ``include/igaparam.h``.

The header is the specification: cbindgen writes it from the Rust sources, and this script
turns its constants, enums, structs, callback types and prototypes, with their documentation
comments, into Python. ``python3 gen_ffi.py`` writes the module; ``--check`` only compares and
exits with status 1 when the checked-in module is stale. ``IGAPARAM_BLESS=1 cargo test --test
header`` regenerates the header and then this module; without it the test fails on either one
being stale.

The header is cbindgen's regular output (one declaration per statement, ``/** */`` comments
before the item they document), and the parser reads only that shape: anything else is an
error naming the line, so that a change of the generator's output cannot go unnoticed.
Standard library only.
"""

import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
HEADER = HERE.parent.parent / "include" / "igaparam.h"
OUTPUT = HERE / "igaparam" / "_ffi.py"

SCALARS = {
    "double": "ctypes.c_double",
    "float": "ctypes.c_float",
    "int": "ctypes.c_int",
    "char": "ctypes.c_char",
    "int8_t": "ctypes.c_int8",
    "uint8_t": "ctypes.c_uint8",
    "int16_t": "ctypes.c_int16",
    "uint16_t": "ctypes.c_uint16",
    "int32_t": "ctypes.c_int32",
    "uint32_t": "ctypes.c_uint32",
    "int64_t": "ctypes.c_int64",
    "uint64_t": "ctypes.c_uint64",
    "size_t": "ctypes.c_size_t",
}


class HeaderError(Exception):
    """The header has a shape this generator does not read."""


def fingerprint(text):
    """FNV-1a (64 bits) of the header's declarations: comments removed, runs of white space
    made one space. ``build.rs`` computes the same number, and the library returns it from
    ``igaparam_abi_fingerprint``: a package and a library built from different declarations
    do not match, whatever their comments say."""
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r"//[^\n]*", " ", text)
    text = " ".join(text.split())
    value = 0xCBF29CE484222325
    for byte in text.encode("utf-8"):
        value = ((value ^ byte) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return value


def python_name(c_name):
    """``igaparam_relocate_options`` → ``RelocateOptions``."""
    return "".join(part.capitalize() for part in c_name.removeprefix("igaparam_").split("_"))


class Header:
    """The declarations of the header, in its order."""

    def __init__(self, text):
        self.items = []  # (kind, name, data, doc)
        self.kinds = {}  # C type name -> "enum" | "alias" | "opaque" | "struct" | "callback"
        self.lines = text.split("\n")
        self.i = 0
        self.doc = ""
        while self.i < len(self.lines):
            self.statement()

    def fail(self, what):
        raise HeaderError(f"include/igaparam.h line {self.i + 1}: {what}: {self.lines[self.i]!r}")

    def add(self, kind, name, data):
        self.items.append((kind, name, data, self.doc))
        if kind != "define" and kind != "function":
            self.kinds[name] = kind
        self.doc = ""

    def take_doc(self):
        """Reads a ``/** ... */`` block starting at the current line."""
        body = []
        while True:
            line = self.lines[self.i].strip()
            self.i += 1
            if line.startswith("/**"):
                line = line[3:]
            end = line.endswith("*/")
            if end:
                line = line[:-2]
            line = line.strip()
            body.append(line[2:] if line.startswith("* ") else line.lstrip("*"))
            if end:
                break
        self.doc = "\n".join(body).strip()

    def until(self, closing):
        """Lines from the current one to the first that matches ``closing``, joined."""
        start = self.i
        while not re.search(closing, self.lines[self.i]):
            self.i += 1
            if self.i == len(self.lines):
                self.i = start
                self.fail("unterminated declaration")
        self.i += 1
        return self.lines[start : self.i]

    def statement(self):
        line = self.lines[self.i]
        stripped = line.strip()
        if stripped.startswith("/**"):
            return self.take_doc()
        if not stripped or stripped.startswith(("#include", "#if", "#endif", "/*", " *", "*")):
            self.i += 1
            return None
        if stripped in ('extern "C" {', '}  // extern "C"'):
            self.i += 1
            return None
        match = re.fullmatch(r"#define (\w+)(?: (.+))?", stripped)
        if match:
            self.i += 1
            if match.group(2) is not None:
                self.add("define", match.group(1), match.group(2))
            return None
        if stripped == "typedef enum {":
            return self.enum()
        if stripped == "typedef struct {":
            return self.struct()
        text = " ".join(part.strip() for part in self.until(r";\s*$"))
        return self.declaration(text)

    def declaration(self, text):
        match = re.fullmatch(r"typedef struct (\w+) (\w+);", text)
        if match and match.group(1) == match.group(2):
            return self.add("opaque", match.group(1), None)
        match = re.fullmatch(r"typedef (\w+) (\w+);", text)
        if match:
            return self.add("alias", match.group(2), match.group(1))
        match = re.fullmatch(r"typedef (.+?)\(\*(\w+)\)\((.*)\);", text)
        if match:
            return self.add("callback", match.group(2), (match.group(1), parameters(match.group(3))))
        match = re.fullmatch(r"(.+?)\b(igaparam_\w+)\((.*)\);", text)
        if match:
            return self.add("function", match.group(2), (match.group(1), parameters(match.group(3)), text))
        return self.fail("unknown declaration")

    def members(self, pattern):
        """(name, value, doc) of the members of a ``{ ... } name;`` body; returns them and the name."""
        self.i += 1
        members = []
        while True:
            stripped = self.lines[self.i].strip()
            if stripped.startswith("/**"):
                self.take_doc()
                continue
            match = re.fullmatch(r"\} (\w+);", stripped)
            if match:
                self.i += 1
                return members, match.group(1)
            match = re.fullmatch(pattern, stripped)
            if not match:
                self.fail("unknown member")
            members.append((*match.groups(), self.doc))
            self.doc = ""
            self.i += 1

    def enum(self):
        doc = self.doc
        members, name = self.members(r"(\w+) = (-?\d+),")
        self.doc = doc
        self.add("enum", name, members)

    def struct(self):
        doc = self.doc
        members, name = self.members(r"(.+?)\s*\b(\w+)(?:\[(\w+)\])?;")
        self.doc = doc
        self.add("struct", name, members)


def parameters(text):
    """[(type, name)] of a C parameter list."""
    text = text.strip()
    if text in ("", "void"):
        return []
    result = []
    for part in text.split(","):
        match = re.fullmatch(r"(.+?)\s*\b(\w+)", part.strip())
        if not match:
            raise HeaderError(f"include/igaparam.h: unreadable parameter {part!r}")
        result.append((match.group(1), match.group(2)))
    return result


class Writer:
    """Python source of the declarations."""

    def __init__(self, header):
        self.header = header
        self.names = {}  # C type name -> Python expression

    def ctype(self, c_type):
        """The ctypes expression of a C type (``None`` for ``void``)."""
        stars = c_type.count("*")
        base = " ".join(word for word in c_type.replace("*", " ").split() if word != "const")
        kind = self.header.kinds.get(base)
        if base == "void":
            return ["None", "ctypes.c_void_p", "ctypes.POINTER(ctypes.c_void_p)"][stars]
        if base == "char" and stars == 1:
            return "ctypes.c_char_p"
        if kind == "opaque":
            if stars == 0:
                raise HeaderError(f"include/igaparam.h: opaque {base} used by value")
            expression, stars = "ctypes.c_void_p", stars - 1
        elif kind in ("enum", "alias"):
            expression = "ctypes.c_int" if kind == "enum" else self.ctype(self.alias(base))
        elif base in self.names:
            expression = self.names[base]
        elif base in SCALARS:
            expression = SCALARS[base]
        else:
            raise HeaderError(f"include/igaparam.h: unknown type {c_type!r}")
        for _ in range(stars):
            expression = f"ctypes.POINTER({expression})"
        return expression

    def alias(self, name):
        return next(data for kind, item, data, _ in self.header.items if kind == "alias" and item == name)

    def source(self):
        out = [PREAMBLE.format(fingerprint=fingerprint(HEADER_TEXT[0]))]
        for kind, name, data, doc in self.header.items:
            method = getattr(self, "write_" + kind)
            out.append(method(name, data, doc))
        out.append(self.write_prototypes())
        source = "\n".join(part for part in out if part)
        return re.sub(r"\n{3,}", "\n\n\n", source).rstrip("\n") + "\n"

    def write_define(self, name, value, doc):
        if not re.fullmatch(r"-?\d+(\.\d*)?([eE]-?\d+)?", value):
            raise HeaderError(f"include/igaparam.h: #define {name} {value} is not a number")
        return f"{comment(doc)}{name.removeprefix('IGAPARAM_')} = {value}\n"

    def write_enum(self, name, members, doc):
        prefix = common_prefix([member for member, _, _ in members])
        lines = [f"\n\nclass {python_name(name)}(enum.IntEnum):", indent(docstring(doc + f"\n\n(``{name}``)"))]
        for member, value, member_doc in members:
            lines.append(f"    {member.removeprefix(prefix)} = {value}")
            if member_doc:
                lines.append(indent(docstring(member_doc)))
        lines.append("\n")
        return "\n".join(lines)

    def write_alias(self, name, target, doc):
        return f"{comment(doc)}# typedef {target} {name}\n"

    def write_opaque(self, name, _, doc):
        return f"{comment(doc)}# {name} * is passed as ctypes.c_void_p\n"

    def write_callback(self, name, data, doc):
        restype, params = data
        python = name.removeprefix("igaparam_").upper()
        self.names[name] = python
        types = ", ".join([self.ctype(restype)] + [self.ctype(t) for t, _ in params])
        signature = ", ".join(f"{t} {n}" for t, n in params)
        return f"{comment(doc)}# {restype.strip()} (*{name})({signature})\n{python} = ctypes.CFUNCTYPE({types})\n"

    def write_struct(self, name, fields, doc):
        python = python_name(name)
        self.names[name] = python
        described = "\n".join(f"{field}:\n{indent(field_doc or '(undocumented)')}" for _, field, _, field_doc in fields)
        lines = [
            f"\n\nclass {python}(ctypes.Structure):",
            indent(docstring(f"{doc}\n\n(``{name}``)\n\nFields:\n\n{described}")),
            "",
            "    _fields_ = [",
        ]
        for c_type, field, length, _ in fields:
            expression = self.ctype(c_type)
            if length:
                expression = f"{expression} * {length.removeprefix('IGAPARAM_')}"
            lines.append(f'        ("{field}", {expression}),')
        lines.append("    ]\n\n")
        return "\n".join(lines)

    def write_function(self, name, data, doc):
        return ""

    def write_prototypes(self):
        lines = ["\n# name: (restype, argtypes, documentation)", "PROTOTYPES = {"]
        for kind, name, data, doc in self.header.items:
            if kind != "function":
                continue
            restype, params, text = data
            args = ", ".join(self.ctype(t) for t, _ in params)
            documentation = f"{text}\n\n{doc}" if doc else text
            lines.append(f'    "{name}": (\n        {self.ctype(restype)},\n        [{args}],')
            lines.append(f"        {literal(documentation)},\n    ),")
        lines.append("}")
        return "\n".join(lines)


def common_prefix(names):
    """The longest prefix ending in ``_`` that all names share."""
    prefix = names[0]
    for name in names[1:]:
        while not name.startswith(prefix):
            prefix = prefix[:-1]
    return prefix[: prefix.rfind("_") + 1]


def literal(text):
    """A Python string literal of ``text``."""
    return repr(text)


def docstring(text):
    text = text.strip().replace("\\", "\\\\").replace('"""', '\\"\\"\\"')
    if text.endswith('"'):
        text += " "
    return f'"""{text}"""' if "\n" not in text else f'"""{text}\n"""'


def indent(text, by="    "):
    return "\n".join(by + line if line else line for line in text.split("\n"))


def comment(doc):
    return "".join(f"# {line}".rstrip() + "\n" for line in doc.split("\n")) if doc else ""


PREAMBLE = '''"""ctypes declarations of the C API, generated from ``include/igaparam.h``; do not edit.

Regenerate with ``IGAPARAM_BLESS=1 cargo test --test header`` (which runs
``bindings/python/gen_ffi.py`` after cbindgen). Structures and enums carry the Python names
of their C types (``igaparam_relocate_options`` is ``RelocateOptions``), constants lose the
``IGAPARAM_`` prefix, and ``PROTOTYPES`` maps every function to its ctypes ``restype``,
``argtypes`` and documentation. Use :mod:`igaparam` rather than this module.
"""

import ctypes
import enum

# The fingerprint of the header's declarations (see ``igaparam_abi_fingerprint``): the loader
# refuses a library built from other declarations instead of calling it with wrong layouts.
ABI_FINGERPRINT = {fingerprint:#018x}
'''

HEADER_TEXT = [""]


def generate(text):
    """The module's source for the header text ``text``."""
    HEADER_TEXT[0] = text
    return Writer(Header(text)).source()


def main(argv):
    check = "--check" in argv
    try:
        source = generate(HEADER.read_text(encoding="utf-8"))
    except HeaderError as error:
        print(f"gen_ffi: {error}", file=sys.stderr)
        return 2
    current = OUTPUT.read_text(encoding="utf-8") if OUTPUT.exists() else ""
    if current == source:
        return 0
    if check:
        print(f"gen_ffi: {OUTPUT} is stale: regenerate it with `IGAPARAM_BLESS=1 cargo test --test header`", file=sys.stderr)
        return 1
    OUTPUT.write_text(source, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
