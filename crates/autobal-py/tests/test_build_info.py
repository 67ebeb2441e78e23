"""`_autobal.build_info()`: how the extension was compiled, which bench/scaling.py uses to refuse
comparing a dev-profile extension with the release CLI. Checked against the compiled file itself
(an independent route), so a build_info that lied would fail here."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from autobal import _autobal


def test_build_info_keys_and_types():
    info = _autobal.build_info()
    assert set(info) == {"profile", "opt_level", "debug_assertions", "debug_info"}
    assert info["profile"] in ("release", "debug")
    assert info["opt_level"] in ("0", "1", "2", "3", "s", "z")
    assert isinstance(info["debug_assertions"], bool)
    assert isinstance(info["debug_info"], bool)
    # a fresh dict each call: a caller may change it without changing the next answer
    info["profile"] = "x"
    assert _autobal.build_info()["profile"] != "x"


def _elf() -> bytes:
    so = Path(_autobal.__file__)
    data = so.read_bytes()
    if not (sys.platform.startswith("linux") and data[:4] == b"\x7fELF"):
        pytest.skip(f"the cross-check reads an ELF extension; {so.name} is not one")
    return data


def _section_names(data: bytes) -> set:
    """The section names of a 64-bit little-endian ELF file (its section header string table)."""
    assert data[4] == 2 and data[5] == 1, "a 64-bit little-endian ELF file"
    shoff = int.from_bytes(data[0x28:0x30], "little")
    shentsize = int.from_bytes(data[0x3A:0x3C], "little")
    shnum = int.from_bytes(data[0x3C:0x3E], "little")
    shstrndx = int.from_bytes(data[0x3E:0x40], "little")

    def header(i):
        h = data[shoff + i * shentsize : shoff + (i + 1) * shentsize]
        return int.from_bytes(h[0:4], "little"), int.from_bytes(h[0x18:0x20], "little"), int.from_bytes(h[0x20:0x28], "little")

    _, stroff, strsize = header(shstrndx)
    strtab = data[stroff : stroff + strsize]
    names = set()
    for i in range(shnum):
        name = header(i)[0]
        names.add(strtab[name : strtab.index(b"\0", name)].decode())
    return names


def test_build_info_debug_assertions_match_the_binary():
    """Debug assertions compile in the standard library's precondition checks of unsafe calls
    (`ub_checks`, which follow the crate's debug assertions), whose panic message is then in the
    binary; a build without them has none. The dev wheel of scripts/test.sh has them on."""
    data = _elf()
    has_checks = b"unsafe precondition(s) violated" in data
    assert _autobal.build_info()["debug_assertions"] == has_checks


def test_build_info_debug_info_matches_the_binary():
    """Debug info (the dev profile's line tables) is a `.debug_line` section of the file; the
    release profile (`debug = false`) has its debug info stripped."""
    data = _elf()
    assert _autobal.build_info()["debug_info"] == (".debug_line" in _section_names(data))
