"""Checks a tactile dataset written by the tactile_rig example the way a Python user reads it,
with the standard library only: index.csv through csv.DictReader, each depth file's .npy header
through ast.literal_eval (as numpy.load parses it) and its data length, each image's PNG
signature. Usage: python3 scripts/check_tactile_dataset.py DIR"""

import ast
import csv
import struct
import sys
from pathlib import Path


def check_npy(path: Path) -> tuple:
    data = path.read_bytes()
    assert data[:6] == b"\x93NUMPY", f"{path}: not a .npy file"
    (header_len,) = struct.unpack("<H", data[8:10])
    assert (10 + header_len) % 64 == 0, f"{path}: the data is not 64-byte aligned"
    header = ast.literal_eval(data[10 : 10 + header_len].decode("latin1"))
    assert header["descr"] == "<f4" and header["fortran_order"] is False, f"{path}: {header}"
    count = 1
    for dimension in header["shape"]:
        count *= dimension
    assert len(data) - 10 - header_len == 4 * count, f"{path}: {len(data)} bytes for {header}"
    depths = struct.unpack(f"<{count}f", data[10 + header_len :])
    assert all(0.0 < d < 1.0 for d in depths), f"{path}: depths outside (0, 1) m"
    return header["shape"]


def main() -> None:
    folder = Path(sys.argv[1])
    with open(folder / "index.csv", newline="") as index:
        rows = list(csv.DictReader(index))
    assert rows, "index.csv has no samples"
    for row in rows:
        shape = check_npy(folder / row["depth"])
        assert (folder / row["image"]).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", row["image"]
        assert row["in_contact"] == "true", row
        assert float(row["max_indentation_mm"]) > 0 and float(row["depth_mm"]) > 0, row
    print(f"{len(rows)} samples of {rows[0]['sensor']}, depth {shape}, read back from {folder}")


if __name__ == "__main__":
    main()
