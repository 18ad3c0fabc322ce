# SPDX-License-Identifier: GPL-3.0-or-later
"""The release's Linux binaries load on the studio baseline (glibc 2.28) and carry their own
C++ runtime:
    PYTHON check_release_binaries.py DIST
(PYTHON: the release venv's, which has auditwheel and pyelftools.)

- `auditwheel show` reports each wheel consistent with manylinux_2_28 or an older policy;
- every ELF file in the wheels and the command-line archive asks for no glibc symbol version
  above 2.28, no libstdc++ (GLIBCXX_, CXXABI_) at all, and only the base libraries every
  manylinux wheel may take from the system;
- none of them exports a symbol of the C++ runtime linked into it (std::, __cxa_, the ABI's
  type info): two copies in one process (the module and the GL plugin, or Blender's own
  runtime) each keep to themselves;
- the extension zip names the platform and both Pythons' wheels in its manifest and holds them."""

import glob
import io
import os
import re
import subprocess
import sys
import tomllib
import unittest
import zipfile

from elftools.elf.dynamic import DynamicSection
from elftools.elf.elffile import ELFFile
from elftools.elf.gnuversions import GNUVerNeedSection

DIST = sys.argv[1] if len(sys.argv) > 1 else ""
GLIBC_CEILING = (2, 28)
BASE_LIBRARIES = {
    "libc.so.6",
    "libm.so.6",
    "libdl.so.2",
    "librt.so.1",
    "libpthread.so.0",
    "ld-linux-x86-64.so.2",
}
# Mangled names of the C++ runtime: std:: (_ZNSt, _ZSt, _ZNKSt, and libc++'s std::__1), the
# C++ ABI (__cxa_*, __cxxabiv1), and operator new/delete.
RUNTIME_SYMBOL = re.compile(r"^(_ZN?K?St|_ZNSt3__1|_ZSt|__cxa_|_ZN10__cxxabiv1|_ZTIN10__cxxabiv1|_Znw|_Zna|_Zdl|_Zda)")


def elf_files():
    """(archive, member, ELFFile) of every ELF file in the wheels and the CLI archives."""
    archives = sorted(glob.glob(os.path.join(DIST, "hyvox-*.whl")) + glob.glob(os.path.join(DIST, "hyvox-*-cli.zip")))
    for archive in archives:
        with zipfile.ZipFile(archive) as z:
            for name in z.namelist():
                data = z.read(name)
                if data[:4] == b"\x7fELF":
                    yield os.path.basename(archive), name, ELFFile(io.BytesIO(data))


def needed_versions(elf):
    """{library: [version names]} the file asks for."""
    out = {}
    for section in elf.iter_sections():
        if isinstance(section, GNUVerNeedSection):
            for verneed, auxes in section.iter_versions():
                out.setdefault(verneed.name, []).extend(aux.name for aux in auxes)
    return out


def needed_libraries(elf):
    for section in elf.iter_sections():
        if isinstance(section, DynamicSection):
            return [tag.needed for tag in section.iter_tags() if tag.entry.d_tag == "DT_NEEDED"]
    return []


def exported_runtime_symbols(elf):
    dynsym = elf.get_section_by_name(".dynsym")
    if dynsym is None:
        return []
    return [
        s.name
        for s in dynsym.iter_symbols()
        if s["st_shndx"] != "SHN_UNDEF"
        and s["st_info"]["bind"] in ("STB_GLOBAL", "STB_WEAK")
        and RUNTIME_SYMBOL.match(s.name)
    ]


class ReleaseBinariesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.files = list(elf_files())
        cls.wheels = sorted(glob.glob(os.path.join(DIST, "hyvox-*.whl")))

    def test_there_is_something_to_check(self):
        tags = sorted(re.search(r"-(cp\d+)-", os.path.basename(w)).group(1) for w in self.wheels)
        self.assertEqual(tags, ["cp311", "cp313"])
        names = {os.path.basename(member) for _, member, _ in self.files}
        # Per wheel: the module, the command, the GL plugin, the mesh reader program.
        self.assertTrue({"hyvox", "libhyvox_gl_methods.so", "hyvox_assimp_reader"} <= names, names)
        self.assertEqual(len([n for n in names if n.startswith("_core.")]), 2, names)

    def test_auditwheel_confirms_manylinux_2_28(self):
        for wheel in self.wheels:
            shown = subprocess.run(
                [sys.executable, "-m", "auditwheel", "show", wheel], capture_output=True, text=True, check=True
            ).stdout
            shown = " ".join(shown.split())
            match = re.search(r'consistent with the following platform tag: "manylinux_(\d+)_(\d+)_x86_64"', shown)
            self.assertIsNotNone(match, shown)
            self.assertLessEqual((int(match.group(1)), int(match.group(2))), GLIBC_CEILING, shown)

    def test_no_glibc_symbol_above_2_28_and_no_libstdcxx(self):
        for archive, member, elf in self.files:
            for library, versions in needed_versions(elf).items():
                for version in versions:
                    self.assertFalse(
                        version.startswith(("GLIBCXX_", "CXXABI_")), f"{archive}:{member} needs {version} of {library}"
                    )
                    if version.startswith("GLIBC_") and version != "GLIBC_PRIVATE":
                        number = tuple(int(p) for p in version[len("GLIBC_") :].split("."))
                        self.assertLessEqual(number[:2], GLIBC_CEILING, f"{archive}:{member} needs {version}")

    def test_only_base_libraries_needed(self):
        for archive, member, elf in self.files:
            extra = set(needed_libraries(elf)) - BASE_LIBRARIES
            self.assertEqual(extra, set(), f"{archive}:{member}")

    def test_cxx_runtime_symbols_stay_inside(self):
        for archive, member, elf in self.files:
            self.assertEqual(exported_runtime_symbols(elf)[:5], [], f"{archive}:{member}")

    def test_extension_holds_both_wheels(self):
        (extension,) = glob.glob(os.path.join(DIST, "hyvox_blender-*-linux_x64.zip"))
        with zipfile.ZipFile(extension) as z:
            manifest = tomllib.loads(z.read("blender_manifest.toml").decode())
            inside = {n for n in z.namelist() if n.startswith("wheels/") and not n.endswith("/")}
        self.assertEqual(manifest["platforms"], ["linux-x64"])
        self.assertEqual(sorted(manifest["wheels"]), sorted("./" + n for n in inside))
        self.assertEqual(sorted(os.path.basename(n) for n in inside), [os.path.basename(w) for w in self.wheels])


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
