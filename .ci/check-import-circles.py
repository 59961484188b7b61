#!/usr/bin/env python3
"""Fails when modules of a crate import each other in a circle.

For every module folder of every crate (`src/`, `src/compose/`, …) it builds the graph of which
sibling module uses which (through `crate::path::to::sibling` or `super::sibling`, comments and
`#[cfg(test)] mod tests` left out) and reports every circle.
"""

import pathlib
import re
import sys

CRATES = ["yarok-core", "yarok-mjc", "yarok-hw", "yarok-components", "yarok-test", "."]
SKIP = {"sys"}  # generated bindings


def code(path):
    text = path.read_text()
    text = re.sub(r"(?s)#\[cfg\(test\)\]\s*mod tests\s*\{.*", "", text)
    return "\n".join(line for line in text.split("\n") if not line.strip().startswith("//"))


def sibling_of(folder, path):
    """The sibling module (directly in `folder`) that `path` belongs to, or None."""
    relative = path.relative_to(folder).with_suffix("")
    first = relative.parts[0]
    return None if first in ("lib", "main", "mod") and len(relative.parts) == 1 else first


def graph(src, folder):
    """Sibling module -> siblings it uses, for the modules directly in `folder`."""
    prefix = "crate" + "".join("::" + p for p in folder.relative_to(src).parts)
    edges = {}
    for path in folder.rglob("*.rs"):
        module = sibling_of(folder, path)
        if module is None or module in SKIP:
            continue
        relative = path.relative_to(folder)
        depth = len(relative.parts) - (1 if relative.name == "mod.rs" else 0)
        supers = "super::" * depth
        text = code(path)
        used = set(re.findall(re.escape(prefix) + r"::([a-z_]+)", text))
        used |= set(re.findall(r"(?<![a-z_:])" + re.escape(supers) + r"([a-z_]+)", text))
        edges.setdefault(module, set()).update(used - {module})
    return edges


def circles(edges):
    found = set()

    def walk(node, path):
        for target in edges.get(node, ()):
            if target in path:
                cycle = path[path.index(target):]
                start = cycle.index(min(cycle))
                found.add(tuple(cycle[start:] + cycle[:start]))
            else:
                walk(target, path + [target])

    for node in edges:
        walk(node, [node])
    return found


def main():
    failures = []
    for crate in CRATES:
        src = pathlib.Path(crate) / "src"
        for folder in [src] + [d for d in src.rglob("*") if d.is_dir()]:
            for cycle in sorted(circles(graph(src, folder))):
                failures.append(f"{folder}: {' -> '.join(cycle + (cycle[0],))}")
    for failure in failures:
        print(f"import circle in {failure}", file=sys.stderr)
    if failures:
        sys.exit(1)
    print("no import circles")


if __name__ == "__main__":
    main()
