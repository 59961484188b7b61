"""The extension's type information (``_native.pyi``, ``py.typed``), checked by mypy: its
``stubtest`` finds the stub true to the compiled module (every name, signature and default),
and ``mypy --strict`` passes on every Python example of the README and the book (``docs/src``;
calls into Gymnasium, whose ``close`` is not annotated, excepted; LeRobot, not installed beside
the type checker, is unknown to it)."""

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs" / "src").glob("*.md"))]


def test_the_stub_matches_the_compiled_module():
    checked = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "yarok._native"],
        capture_output=True,
        text=True,
    )
    assert checked.returncode == 0, checked.stdout + checked.stderr


def test_the_python_examples_of_the_readme_and_the_book_type_check_strictly(tmp_path):
    sources = []
    for document in DOCUMENTS:
        blocks = re.findall(r"```python\n(.*?)```", document.read_text(), re.S)
        for number, block in enumerate(blocks):
            source = tmp_path / f"{document.stem.replace('-', '_')}_{number}.py"
            source.write_text(block)
            sources.append(source)
    assert any("yarok.World(" in source.read_text() for source in sources)
    # One run over every block, each its own module: mypy's errors name the block's file.
    checked = subprocess.run(
        [
            sys.executable,
            "-m",
            "mypy",
            "--strict",
            "--untyped-calls-exclude=gymnasium",
            "--ignore-missing-imports",
            "--no-incremental",
            *map(str, sources),
        ],
        capture_output=True,
        text=True,
    )
    assert checked.returncode == 0, checked.stdout + checked.stderr
