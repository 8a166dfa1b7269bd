"""The ctypes mirror (python/obscura/_abi.py) against the C compiler's view of obscura.h: every
struct's size, every field's name and offset, every enum value. The C is generated from the mirror,
so a misspelt field fails to compile and a moved one prints another offset."""

from __future__ import annotations

import ctypes
import subprocess
from pathlib import Path

from conftest import environment
from obscura import _abi

# C names of the mirrored enums' values: prefix by Python enum (Status.OK is OBSCURA_OK).
PREFIXES = {_abi.Status: "OBSCURA_ERROR_", _abi.ValueType: "OBSCURA_VALUE_", _abi.Interpolation:
            "OBSCURA_INTERPOLATION_", _abi.Dirty: "OBSCURA_DIRTY_", _abi.StructureType: "OBSCURA_STRUCTURE_TYPE_",
            _abi.LogLevel: "OBSCURA_LOG_", _abi.Format: "OBSCURA_FORMAT_"}
SCALARS = {"OBSCURA_ABI_VERSION_MAJOR": _abi.ABI_VERSION_MAJOR, "OBSCURA_ABI_VERSION_MINOR": _abi.ABI_VERSION_MINOR,
           "OBSCURA_SCENE_DELEGATE_THREAD_SAFE": _abi.SCENE_DELEGATE_THREAD_SAFE, "OBSCURA_OK": _abi.Status.OK}


def c_name(field: str) -> str:
    return "pass" if field == "pass_" else field


def expected_lines() -> list[tuple[str, str, int]]:
    """(label, C expression, the mirror's value)."""
    lines = []
    for name, struct in _abi.STRUCTS.items():
        lines.append((f"sizeof {name}", f"sizeof({name})", ctypes.sizeof(struct)))
        for field, _ in struct._fields_:
            offset = getattr(struct, field).offset
            lines.append((f"{name}.{field}", f"offsetof({name}, {c_name(field)})", offset))
    for cls, prefix in PREFIXES.items():
        for member in cls:
            if member is _abi.Status.OK:
                continue
            lines.append((f"{cls.__name__}.{member.name}", f"(unsigned long long)({prefix}{member.name})", int(member)))
    lines += [(name, f"(unsigned long long)({name})", int(value)) for name, value in SCALARS.items()]
    lines.append(("OBSCURA_GET_API_SYMBOL", f'strcmp(OBSCURA_GET_API_SYMBOL, "{_abi.GET_API_SYMBOL}") == 0', 1))
    return lines


def test_mirror_matches_the_header(tmp_path: Path) -> None:
    lines = expected_lines()
    source = ["#include <obscura/obscura.h>", "#include <stddef.h>", "#include <stdio.h>", "#include <string.h>",
              "int main(void) {"]
    source += [f'    printf("%llu\\n", (unsigned long long)({expr}));' for _, expr, _ in lines]
    source += ["    return 0;", "}"]
    (tmp_path / "layout.c").write_text("\n".join(source) + "\n")
    compiler, include = environment("OBSCURA_TEST_C_COMPILER"), environment("OBSCURA_TEST_INCLUDE_DIR")
    subprocess.run([compiler, "-std=c99", "-Wall", "-Werror", "-I", include, "-o", str(tmp_path / "layout"),
                    str(tmp_path / "layout.c")], check=True)
    printed = subprocess.run([str(tmp_path / "layout")], capture_output=True, text=True, check=True).stdout.split()
    assert len(printed) == len(lines)
    mismatches = [(label, int(c), mine) for (label, _, mine), c in zip(lines, printed) if int(c) != mine]
    assert mismatches == []
