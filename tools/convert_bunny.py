#!/usr/bin/python3
"""Converts the Stanford bunny of the npm package `bunny` into assets/meshes/bunny.obj.

Usage: tools/convert_bunny.py PACKAGE [OUT.obj]
  PACKAGE  the tarball from `npm pack bunny` (bunny-1.0.1.tgz) or its unpacked index.js
  OUT.obj  default: assets/meshes/bunny.obj beside this script's repository

The package's index.js holds two JavaScript arrays, `exports.positions` ([x, y, z] per vertex)
and `exports.cells` (three 0-based vertex indices per triangle). They are written unchanged
(every vertex and triangle kept, same order) as an OBJ with 1-based indices. The script reports
the boundary edges (edges used by one triangle): the scan is not closed where those exist.
Standard library only.
"""

import json
import pathlib
import re
import sys
import tarfile
from collections import Counter


def read_source(package: pathlib.Path) -> str:
    if package.suffix in (".tgz", ".gz"):
        with tarfile.open(package) as archive:
            member = archive.extractfile("package/index.js")
            if member is None:
                sys.exit(f"{package}: no package/index.js inside")
            return member.read().decode("utf-8")
    return package.read_text(encoding="utf-8")


def js_array(source: str, name: str):
    match = re.search(r"exports\." + name + r"\s*=\s*(\[.*?\]\])", source, re.S)
    if not match:
        sys.exit(f"no exports.{name} array found")
    return json.loads(match.group(1))


def main() -> None:
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    package = pathlib.Path(sys.argv[1])
    root = pathlib.Path(__file__).resolve().parent.parent
    out = pathlib.Path(sys.argv[2]) if len(sys.argv) == 3 else root / "assets/meshes/bunny.obj"

    source = read_source(package)
    positions = js_array(source, "positions")
    cells = js_array(source, "cells")
    for p in positions:
        if len(p) != 3:
            sys.exit(f"a position has {len(p)} coordinates")
    for c in cells:
        if len(c) != 3 or not all(0 <= i < len(positions) for i in c):
            sys.exit(f"bad triangle {c}")

    # Boundary edges: an undirected edge used by exactly one triangle.
    edges = Counter()
    for a, b, c in cells:
        for u, v in ((a, b), (b, c), (c, a)):
            edges[(min(u, v), max(u, v))] += 1
    boundary = sum(1 for n in edges.values() if n == 1)

    lines = [
        "# The Stanford bunny (Stanford 3D Scanning Repository, Greg Turk and Marc Levoy, 1994),",
        "# from the npm package `bunny` 1.0.1 by Mikola Lysenko (licence: Public Domain).",
        "# Converted by tools/convert_bunny.py: vertices and triangles unchanged.",
        f"# {len(positions)} vertices, {len(cells)} triangles, {boundary} boundary edges.",
    ]
    lines += ["v {} {} {}".format(*(repr(float(x)) for x in p)) for p in positions]
    lines += ["f {} {} {}".format(*(i + 1 for i in c)) for c in cells]
    out.parent.mkdir(parents=True, exist_ok=True)
    temporary = out.with_suffix(".obj.tmp")
    temporary.write_text("\n".join(lines) + "\n", encoding="ascii")
    temporary.replace(out)
    print(f"{out}: {len(positions)} vertices, {len(cells)} triangles, {boundary} boundary edges")


if __name__ == "__main__":
    main()
