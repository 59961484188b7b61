"""The extension's type information (``_native.pyi``, ``py.typed``), checked by mypy: its
``stubtest`` finds the stub true to the compiled module (every name, signature and default),
and ``mypy --strict`` passes on the README's Python (calls into Gymnasium, whose ``close`` is
not annotated, excepted)."""

import re
import subprocess
import sys
from pathlib import Path

README = Path(__file__).resolve().parents[2] / "README.md"


def test_the_stub_matches_the_compiled_module():
    checked = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "yarok._native"],
        capture_output=True,
        text=True,
    )
    assert checked.returncode == 0, checked.stdout + checked.stderr


def test_the_readmes_python_type_checks_strictly(tmp_path):
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), re.S)
    quickstart = next(block for block in blocks if "yarok.World(" in block)
    source = tmp_path / "quickstart.py"
    source.write_text(quickstart)
    checked = subprocess.run(
        [
            sys.executable,
            "-m",
            "mypy",
            "--strict",
            "--untyped-calls-exclude=gymnasium",
            "--no-incremental",
            str(source),
        ],
        capture_output=True,
        text=True,
    )
    assert checked.returncode == 0, checked.stdout + checked.stderr
