"""Runs a benchmark and, when it succeeds, writes what it printed into its section of the
results page:

    python3 scripts/results.py tactile cargo bench --bench tactile

The benchmark's output passes through as it comes. The section of ``docs/src/results.md``
between ``<!-- results:NAME -->`` and ``<!-- /results:NAME -->`` becomes that output, with the
date and the machine's processor count; a page without that section gets it appended under a
heading NAME. A benchmark that fails leaves the page as it was and gives its exit status.
"""

import datetime
import os
import subprocess
import sys
from pathlib import Path

PAGE = Path(__file__).resolve().parent.parent / "docs" / "src" / "results.md"


def section(name: str, printed: str) -> str:
    when = datetime.date.today().isoformat()
    return (
        f"<!-- results:{name} -->\n"
        f"As printed on {when}, {os.cpu_count()} cores:\n\n"
        f"```text\n{printed.rstrip()}\n```\n"
        f"<!-- /results:{name} -->"
    )


def main() -> None:
    if len(sys.argv) < 3:
        sys.exit("usage: python3 scripts/results.py NAME COMMAND [ARGUMENT ...]")
    name, command = sys.argv[1], sys.argv[2:]
    printed = []
    with subprocess.Popen(
        command, stdout=subprocess.PIPE, text=True, env={**os.environ, "PYTHONUNBUFFERED": "1"}
    ) as benchmark:
        assert benchmark.stdout is not None
        for line in benchmark.stdout:
            sys.stdout.write(line)
            sys.stdout.flush()
            printed.append(line)
    if benchmark.returncode != 0:
        sys.exit(benchmark.returncode)
    page = PAGE.read_text()
    start, end = f"<!-- results:{name} -->", f"<!-- /results:{name} -->"
    written = section(name, "".join(printed))
    if start in page and end in page:
        before, rest = page.split(start, 1)
        page = before + written + rest.split(end, 1)[1]
    else:
        page = page.rstrip("\n") + f"\n\n## {name}\n\n{written}\n"
    PAGE.write_text(page)
    print(f"results: {PAGE.relative_to(PAGE.parents[2])} section {name} rewritten", file=sys.stderr)


if __name__ == "__main__":
    main()
