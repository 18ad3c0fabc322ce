# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes the hyvox package's stubs from their templates and the options schema of the built module.

    python gen_stubs.py PACKAGE_PARENT TEMPLATE OUTPUT [TEMPLATE OUTPUT ...]

PACKAGE_PARENT is the folder holding the built hyvox/ package (B/python). Each template may
hold the markers @VOXELIZE_OPTIONS@ (one keyword per option of voxelize()) and
@WRITE_OPTIONS@ (one per option of VoxelGrid.write_vdb() its signature does not already
name), each on a line of its own, indented as the keywords go. Run by the build after the
module is linked, so the stubs can never disagree with the schema."""

import re
import sys

TYPES = {
    "int": "int",
    "float": "float",
    "bool": "bool",
    "str": "str",
    "vector3": "Sequence[float]",
    "box": "Tuple[Sequence[float], Sequence[float]]",
}


def annotation(spec) -> str:
    if spec.type == "choice":
        return "Literal[" + ", ".join(repr(c) for c in spec.choices) + "]"
    if spec.type == "choices":  # the comma list as text, or the names
        return "Union[str, Sequence[Literal[" + ", ".join(repr(c) for c in spec.choices) + "]]]"
    return TYPES[spec.type]


def keyword_lines(options, indent: str) -> str:
    # None = the native default (after environment variables), so every keyword is Optional.
    return "\n".join(f"{indent}{spec.name}: Optional[{annotation(spec)}] = None,  # {spec.help}" for spec in options)


def fill(text: str, marker: str, options, where: str) -> str:
    found = re.findall(rf"^([ \t]*){marker}$", text, flags=re.M)
    if len(found) > 1:
        raise SystemExit(f"{where}: {marker} more than once")
    if not found:
        return text
    indent = found[0]
    # The keywords the signature around the marker names itself (write_vdb's threads).
    signature = text[text.rfind("def ", 0, text.index(marker)) : text.index(marker)]
    named = set(re.findall(r"(\w+):", signature))
    rest = [spec for spec in options if spec.name not in named]
    return text.replace(indent + marker, keyword_lines(rest, indent))


def main(parent: str, *pairs: str) -> None:
    if not pairs or len(pairs) % 2:
        raise SystemExit("usage: gen_stubs.py PACKAGE_PARENT TEMPLATE OUTPUT [TEMPLATE OUTPUT ...]")
    sys.path.insert(0, parent)
    from hyvox import _core  # the freshly built module

    for template, output in zip(pairs[::2], pairs[1::2]):
        with open(template, encoding="utf-8") as f:
            text = f.read()
        filled = fill(text, "@VOXELIZE_OPTIONS@", _core.OPTIONS, template)
        filled = fill(filled, "@WRITE_OPTIONS@", _core.WRITE_OPTIONS, template)
        if filled == text:
            raise SystemExit(f"{template}: has no @VOXELIZE_OPTIONS@ or @WRITE_OPTIONS@ marker")
        with open(output, "w", encoding="utf-8") as f:
            f.write(filled)


if __name__ == "__main__":
    main(*sys.argv[1:])
