# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks that every relative link in the project's Markdown pages resolves: README.md,
CHANGES.md, addon/README.md, bench/README.md, bench/device/README.md and docs/**/*.md (or the
files given). A link `[text](path)` or `<img src="path">` must name a file or folder that
exists, relative to the page; a `#anchor` into a Markdown page must match one of its headings
as GitHub makes them. Web links are not followed. Code blocks and code spans are skipped.
Exit status 1 when a link is broken, each listed. Standard library only.

    python3 docs/check_links.py [PAGE.md...]
"""

import os
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
PAGES = ["README.md", "CHANGES.md", "addon/README.md", "bench/README.md", "bench/device/README.md", "docs/**/*.md"]
LINK = re.compile(r"!?\[(?:[^\]\\]|\\.)*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)|<img\s[^>]*src=\"([^\"]+)\"")
CODE_SPAN = re.compile(r"(`+).*?\1")


def prose_lines(text):
    """(line number, line) outside fenced code blocks, with code spans blanked."""
    fence = None
    for number, line in enumerate(text.splitlines(), 1):
        stripped = line.lstrip()
        if fence:
            if stripped.startswith(fence):
                fence = None
            continue
        if stripped.startswith(("```", "~~~")):
            fence = stripped[:3]
            continue
        yield number, CODE_SPAN.sub("", line)


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"[`*]|<[^>]+>", "", heading.strip().lower())
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def anchors(page):
    found, seen = set(), {}
    for _, line in prose_lines(page.read_text(encoding="utf-8")):
        match = re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
        if match:
            base = slug(match.group(1))
            count = seen.get(base, 0)
            seen[base] = count + 1
            found.add(base if count == 0 else f"{base}-{count}")
    return found


def broken_links(page, counted):
    problems = []
    for number, line in prose_lines(page.read_text(encoding="utf-8")):
        for match in LINK.finditer(line):
            target = match.group(1) or match.group(2)
            if re.match(r"[a-z][a-z0-9+.-]*:", target, re.I):  # https:, mailto:, ...
                continue
            counted.append(target)
            path_text, _, anchor = target.partition("#")
            where = f"{os.path.relpath(page, ROOT)}:{number}: {target}"
            path = (page.parent / path_text).resolve() if path_text else page
            if not path.exists():
                problems.append(f"{where}: no such file")
            elif anchor and path.suffix == ".md" and anchor not in anchors(path):
                problems.append(f"{where}: no heading '#{anchor}' in {os.path.relpath(path, ROOT)}")
    return problems


def main(argv):
    pages = [pathlib.Path(p).resolve() for p in argv] or sorted({p for pattern in PAGES for p in ROOT.glob(pattern)})
    counted = []
    problems = [p for page in pages for p in broken_links(page, counted)]
    for p in problems:
        print(p)
    print(f"check_links: {len(counted)} links in {len(pages)} pages, {len(problems)} broken")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
