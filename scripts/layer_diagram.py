# SPDX-License-Identifier: GPL-3.0-or-later
"""docs/design.md's layer diagram, drawn from the layers the build made (BUILD/layers.txt, which
native/src/CMakeLists.txt writes when it is configured: each library or program of native/src/
and the ones of them it links).

    python3 scripts/layer_diagram.py BUILD           exits 1, with the difference, when the page's
                                                     diagram is not the build's (a CTest test)
    python3 scripts/layer_diagram.py BUILD --write   puts the build's diagram into the page

The diagram lists the targets bottom up: a target's level is one above the highest level of what
it links, so every arrow points to a line above it."""

import argparse
import difflib
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PAGE = os.path.join(ROOT, "docs", "design.md")
BEGIN = "<!-- layers: drawn by scripts/layer_diagram.py from the build; do not edit by hand -->"
END = "<!-- layers: end -->"


def read_links(build: str) -> dict:
    links = {}
    with open(os.path.join(build, "layers.txt"), encoding="utf-8") as file:
        for line in file:
            names = line.split()
            if names:
                links[names[0]] = sorted(set(names[1:]))
    return links


def levels(links: dict) -> dict:
    level = {}

    def of(target, path=()):
        if target in path:
            raise SystemExit(f"layer_diagram: the layers link in a circle: {' -> '.join(path + (target,))}")
        if target not in level:
            level[target] = 1 + max((of(d, path + (target,)) for d in links.get(target, [])), default=-1)
        return level[target]

    for target in links:
        of(target)
    return level


def diagram(links: dict) -> str:
    level = levels(links)
    order = sorted(links, key=lambda t: (level[t], t))
    width = max(len(t) for t in order)
    lines = [f"{t.ljust(width)}  -> {' '.join(links[t])}" if links[t] else t for t in order]
    return "```\n" + "\n".join(line.rstrip() for line in lines) + "\n```"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("build", help="a configured build folder")
    parser.add_argument("--write", action="store_true", help="write the build's diagram into the page")
    args = parser.parse_args()
    drawn = diagram(read_links(args.build))
    with open(PAGE, encoding="utf-8") as file:
        page = file.read()
    if BEGIN not in page or END not in page:
        print(f"layer_diagram: {PAGE} has no diagram between {BEGIN!r} and {END!r}", file=sys.stderr)
        return 1
    head, rest = page.split(BEGIN, 1)
    shown, tail = rest.split(END, 1)
    if args.write:
        with open(PAGE, "w", encoding="utf-8") as file:
            file.write(f"{head}{BEGIN}\n{drawn}\n{END}{tail}")
        return 0
    if shown.strip() != drawn:
        sys.stdout.writelines(
            difflib.unified_diff(
                shown.strip().splitlines(True), (drawn + "\n").splitlines(True), "docs/design.md", "the build"
            )
        )
        print(
            f"\nlayer_diagram: docs/design.md's layers are not the build's: "
            f"python3 scripts/layer_diagram.py {args.build} --write",
            file=sys.stderr,
        )
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
