"""Writes a benchmark's output, saved in a file (or given on stdin), into its section of the
results page:

    cargo bench --bench tactile | tee tactile.txt && python3 scripts/results.py tactile tactile.txt

The section of ``docs/src/results.md`` between ``<!-- results:NAME -->`` and
``<!-- /results:NAME -->`` becomes the output, as printed, with the date and the machine's
processor count; a page without that section gets it appended under a heading NAME.
"""

import datetime
import os
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
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: python3 scripts/results.py NAME [OUTPUT_FILE]")
    name = sys.argv[1]
    printed = [Path(sys.argv[2]).read_text() if len(sys.argv) == 3 else sys.stdin.read()]
    page = PAGE.read_text()
    start, end = f"<!-- results:{name} -->", f"<!-- /results:{name} -->"
    if start in page and end in page:
        before, rest = page.split(start, 1)
        after = rest.split(end, 1)[1]
        page = before + section(name, "".join(printed)) + after
    else:
        page = page.rstrip("\n") + f"\n\n## {name}\n\n{section(name, ''.join(printed))}\n"
    PAGE.write_text(page)
    print(f"results: {PAGE.relative_to(PAGE.parents[2])} section {name} rewritten", file=sys.stderr)


if __name__ == "__main__":
    main()
