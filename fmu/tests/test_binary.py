"""The binary inside the FMUs is portable and stripped (issue 33, item 8): on Linux it needs no
glibc symbol version newer than 2.17 (it loads on manylinux2014-era rig PCs), carries no debug
information and no symbol table, and exports every function FMI 2.0 and 3.0 require."""

from __future__ import annotations

import io
import platform
import re
import zipfile

import pytest
from elftools.elf.elffile import ELFFile
from elftools.elf.gnuversions import GNUVerNeedSection

from fmu_helpers import ALL_FMUS

LINUX = platform.system() == "Linux"
pytestmark = pytest.mark.skipif(not LINUX, reason="the portable build is the Linux one")

GLIBC = (2, 17)
# A selection of the functions each standard requires (importers bind them all at load).
REQUIRED = ["fmi3InstantiateCoSimulation", "fmi3DoStep", "fmi3GetFloat64", "fmi3SetFloat64",
            "fmi3GetFMUState", "fmi3SerializeFMUState", "fmi3DeserializeFMUState",
            "fmi3FreeInstance", "fmi3SetDebugLogging", "fmi3GetVersion",
            "fmi2Instantiate", "fmi2DoStep", "fmi2GetReal", "fmi2SetReal", "fmi2GetFMUstate",
            "fmi2SerializeFMUstate", "fmi2DeSerializeFMUstate", "fmi2GetRealStatus",
            "fmi2GetBooleanStatus", "fmi2SetDebugLogging", "fmi2GetTypesPlatform"]


def binaries() -> list[tuple[str, bytes]]:
    out = []
    for name, path in ALL_FMUS.items():
        with zipfile.ZipFile(path) as z:
            for entry in z.namelist():
                if entry.startswith("binaries/") and entry.endswith(".so"):
                    out.append((f"{name}:{entry}", z.read(entry)))
    assert len(out) == len(ALL_FMUS), "one Linux binary per FMU"
    return out


@pytest.mark.parametrize("name,data", binaries(), ids=lambda x: x if isinstance(x, str) else "")
def test_the_binary_needs_glibc_2_17_at_most_and_is_stripped(name: str, data: bytes) -> None:
    elf = ELFFile(io.BytesIO(data))
    needed = set()
    for section in elf.iter_sections():
        if isinstance(section, GNUVerNeedSection):
            for _, auxiliaries in section.iter_versions():
                for aux in auxiliaries:
                    needed.add(aux.name)
    glibc = sorted(tuple(int(p) for p in re.findall(r"\d+", v)) for v in needed
                   if v.startswith("GLIBC_"))
    assert glibc, "no glibc symbol versions found"
    print(f"{name}: needs {', '.join('GLIBC_' + '.'.join(map(str, v)) for v in glibc)}; "
          f"{len(data) / 1e6:.2f} MB")
    assert max(glibc) <= GLIBC, f"needs GLIBC_{'.'.join(map(str, max(glibc)))} > 2.17"
    assert not [v for v in needed if v.startswith("GLIBCXX_") or v.startswith("CXXABI_")]
    sections = [s.name for s in elf.iter_sections()]
    assert not [s for s in sections if s.startswith(".debug") or s.startswith(".zdebug")], \
        "debug information left in the binary"
    assert ".symtab" not in sections, "not stripped: a symbol table is left"
    # 2.08 MB stripped since the binary also carries the ring's and a model file's matrix
    # stepper (issues 28, 29), under 2 MB before. The bound catches debug info or a std bloat.
    assert len(data) < 3_000_000, f"{len(data) / 1e6:.2f} MB"
    exported = {s.name for s in elf.get_section_by_name(".dynsym").iter_symbols()
                if s["st_shndx"] != "SHN_UNDEF"}
    missing = [f for f in REQUIRED if f not in exported]
    assert not missing, missing
