# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes hyvox/__init__.pyi from its template and the options schema of the built module.

    python gen_stubs.py PACKAGE_PARENT TEMPLATE OUTPUT

PACKAGE_PARENT is the folder holding the built hyvox/ package (B/python). Run by the build
after the module is linked, so the stubs can never disagree with the schema."""
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


def keyword_lines(options) -> str:
    # None = the native default (after environment variables), so every keyword is Optional.
    return "\n".join(f"    {spec.name}: Optional[{annotation(spec)}] = None,  # {spec.help}" for spec in options)


def main(parent: str, template: str, output: str) -> None:
    sys.path.insert(0, parent)
    from hyvox import _core  # the freshly built module

    with open(template, encoding="utf-8") as f:
        text = f.read()
    if text.count("@VOXELIZE_OPTIONS@") != 1:
        raise SystemExit(f"{template}: needs exactly one @VOXELIZE_OPTIONS@ marker")
    text = text.replace("@VOXELIZE_OPTIONS@", keyword_lines(_core.OPTIONS))
    with open(output, "w", encoding="utf-8") as f:
        f.write(text)


if __name__ == "__main__":
    main(*sys.argv[1:])
