"""The README and the book (docs/src) hold together: the README is at most 400 lines, every
chapter is in the book's SUMMARY.md and has its Rust examples run as doc tests (src/lib.rs's
`book` module), and every relative link of the README and the book reaches a file."""

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BOOK = ROOT / "docs" / "src"
MOST_README_LINES = 400

problems = []
readme = ROOT / "README.md"
lines = len(readme.read_text().splitlines())
if lines > MOST_README_LINES:
    problems.append(f"README.md: {lines} lines, more than {MOST_README_LINES}")
summary = (BOOK / "SUMMARY.md").read_text()
listed = set(re.findall(r"\]\(([^)]+\.md)\)", summary))
library = (ROOT / "src" / "lib.rs").read_text()
for chapter in sorted(BOOK.glob("*.md")):
    if chapter.name == "SUMMARY.md":
        continue
    if chapter.name not in listed:
        problems.append(f"docs/src/SUMMARY.md: the chapter {chapter.name} is not listed")
    has_rust = re.search(r"^```rust", chapter.read_text(), re.M)
    if has_rust and f'include_str!("../docs/src/{chapter.name}")' not in library:
        problems.append(f"src/lib.rs: the chapter {chapter.name}'s Rust examples are not doc tests")
for document in [readme, *sorted(BOOK.glob("*.md"))]:
    text = re.sub(r"^```.*?^```", "", document.read_text(), flags=re.S | re.M)
    for line in text.splitlines():
        for target in re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", line):
            if re.match(r"[a-z]+:", target):
                continue
            if not (document.parent / target).exists():
                problems.append(f"{document.relative_to(ROOT)}: the link {target} reaches nothing")
for problem in problems:
    print(problem, file=sys.stderr)
if problems:
    sys.exit(1)
print(f"book: README {lines} lines, {len(listed)} chapters, links reach their files")
