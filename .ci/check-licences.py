#!/usr/bin/env python3
"""Checks that every crate in the dependency graph may be linked into a MIT OR Apache-2.0 framework.

Reads `cargo metadata` (all targets, features and platforms: normal, build and dev dependencies)
and evaluates each package's SPDX licence expression: a package passes when some way of satisfying
its expression uses only permissive licences from ALLOWED, or it is one of MPL_CRATES (MPL-2.0,
unmodified from the registry). The workspace's own crates must be
exactly `MIT OR Apache-2.0`. Prints the offenders and exits 1 if any.
"""

import json
import re
import subprocess
import sys

ALLOWED = {
    "MIT", "MIT-0", "Apache-2.0", "Apache-2.0 WITH LLVM-exception", "BSD-2-Clause", "BSD-3-Clause",
    "ISC", "Zlib", "0BSD", "Unlicense", "CC0-1.0", "BSL-1.0", "Unicode-3.0", "Unicode-DFS-2016",
}
OWN_LICENCE = "MIT OR Apache-2.0"
# MPL-2.0 is file-level copyleft: allowed for these crates, used unmodified from the registry (no
# vendored or patched copy), and for no other.
MPL_CRATES = {"serialport"}


def tokens(expression):
    return re.findall(r"\(|\)|[A-Za-z0-9.+\-]+(?:\s+WITH\s+[A-Za-z0-9.+\-]+)?", expression)


def satisfiable(expression):
    """Evaluates an SPDX expression: OR binds looser than AND; `/` is the legacy OR."""
    items = tokens(expression.replace("/", " OR "))
    position = 0

    def parse_or():
        nonlocal position
        value = parse_and()
        while position < len(items) and items[position] == "OR":
            position += 1
            value = parse_and() or value
        return value

    def parse_and():
        nonlocal position
        value = parse_atom()
        while position < len(items) and items[position] == "AND":
            position += 1
            value = parse_atom() and value
        return value

    def parse_atom():
        nonlocal position
        if position >= len(items):
            raise ValueError(f"unexpected end of {expression!r}")
        item = items[position]
        position += 1
        if item == "(":
            value = parse_or()
            if position >= len(items) or items[position] != ")":
                raise ValueError(f"unbalanced parentheses in {expression!r}")
            position += 1
            return value
        return re.sub(r"\s+", " ", item) in ALLOWED

    value = parse_or()
    if position != len(items):
        raise ValueError(f"cannot parse {expression!r}")
    return value


def self_test():
    """The evaluator itself must tell copyleft from permissive, or the check proves nothing."""
    cases = {
        "MIT OR Apache-2.0": True, "MIT/Apache-2.0": True, "(MIT OR Apache-2.0) AND Unicode-3.0": True,
        "Apache-2.0 WITH LLVM-exception OR MIT": True, "GPL-2.0 OR MIT": True,
        "AGPL-3.0-only": False, "MIT AND GPL-3.0-or-later": False, "MPL-2.0": False,
        "(MIT OR LGPL-2.1) AND AGPL-3.0": False,
    }
    for expression, expected in cases.items():
        assert satisfiable(expression) == expected, f"evaluator wrong on {expression!r}"


def main():
    self_test()
    metadata = json.loads(
        subprocess.run(
            ["cargo", "metadata", "--format-version", "1", "--locked", "--all-features"],
            check=True, capture_output=True, text=True,
        ).stdout
    )
    members = set(metadata["workspace_members"])
    problems = []
    for package in metadata["packages"]:
        name = f"{package['name']} {package['version']}"
        licence = package.get("license")
        if package["id"] in members:
            if licence != OWN_LICENCE:
                problems.append(f"{name}: workspace crate must be {OWN_LICENCE!r}, is {licence!r}")
        elif not licence:
            problems.append(f"{name}: no SPDX licence expression (license-file only)")
        elif package["name"] in MPL_CRATES and licence == "MPL-2.0":
            if not package["source"] or not package["source"].startswith("registry+"):
                problems.append(f"{name}: MPL-2.0 crates must come unmodified from the registry")
        else:
            try:
                if not satisfiable(licence):
                    problems.append(f"{name}: {licence!r} is not permissive")
            except ValueError as error:
                problems.append(f"{name}: {error}")
    for problem in problems:
        print(f"licence check: {problem}")
    print(f"licence check: {len(metadata['packages'])} packages, {len(problems)} problems")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
