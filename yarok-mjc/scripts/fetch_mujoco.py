#!/usr/bin/env python3
"""Fetch MuJoCo 4.0.1 (library and headers) from PyPI's mujoco-core wheel into a cache folder.

Usage: fetch_mujoco.py DEST

The wheel is hash-checked; only `libmujoco.so.4.0.1` and `include/mujoco/*.h` are kept:
    DEST/lib/libmujoco.so.4.0.1
    DEST/include/mujoco/*.h
Running it again when DEST is complete does nothing.
"""

import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import zipfile

VERSION = "4.0.1"
WHEEL = f"mujoco_core-{VERSION}-cp311-cp311-manylinux_2_27_x86_64.manylinux_2_28_x86_64.whl"
SHA256 = "be28c0c7587347ef996b4de0487264e9da296282082b092bae211a9163e9aed6"
LIBRARY = f"libmujoco.so.{VERSION}"

HELP = (
    "yarok needs MuJoCo {version}. Either make `python3 -m pip` work (Debian: `apt-get install "
    "python3-pip`, or `python3 -m ensurepip`) and network access to PyPI, or build/download "
    "MuJoCo {version} yourself and set MUJOCO_DIR to the folder holding lib/{lib} and "
    "include/mujoco/mujoco.h."
).format(version=VERSION, lib=LIBRARY)


def fail(message):
    sys.stderr.write(f"error: {message}\n{HELP}\n")
    sys.exit(1)


def complete(dest):
    return os.path.isfile(os.path.join(dest, "lib", LIBRARY)) and os.path.isfile(
        os.path.join(dest, "include", "mujoco", "mujoco.h")
    )


def download(workdir):
    command = [
        sys.executable, "-m", "pip", "download", "--no-deps", "--only-binary=:all:",
        "--platform", "manylinux_2_28_x86_64", "--python-version", "3.11",
        "--dest", workdir, f"mujoco-core=={VERSION}",
    ]
    try:
        result = subprocess.run(command, capture_output=True, text=True)
    except OSError as error:
        fail(f"could not run pip ({error})")
    if result.returncode != 0:
        fail(f"`{' '.join(command)}` failed:\n{result.stderr.strip()}")
    wheel = os.path.join(workdir, WHEEL)
    if not os.path.isfile(wheel):
        fail(f"pip did not produce {WHEEL} in {workdir}")
    return wheel


def check_hash(wheel):
    digest = hashlib.sha256()
    with open(wheel, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    if digest.hexdigest() != SHA256:
        fail(f"{WHEEL} has sha256 {digest.hexdigest()}, expected {SHA256}")


def extract(wheel, staging):
    os.makedirs(os.path.join(staging, "lib"))
    os.makedirs(os.path.join(staging, "include", "mujoco"))
    with zipfile.ZipFile(wheel) as archive:
        for member in archive.namelist():
            if member == f"mujoco/{LIBRARY}":
                target = os.path.join(staging, "lib", LIBRARY)
            elif member.startswith("mujoco/include/mujoco/") and member.endswith(".h"):
                target = os.path.join(staging, "include", "mujoco", os.path.basename(member))
            else:
                continue
            with archive.open(member) as source, open(target, "wb") as sink:
                shutil.copyfileobj(source, sink)
    if not complete(staging):
        fail(f"{WHEEL} does not hold mujoco/{LIBRARY} and mujoco/include/mujoco/mujoco.h")


def main():
    if len(sys.argv) != 2:
        sys.stderr.write(__doc__)
        sys.exit(2)
    dest = os.path.abspath(sys.argv[1])
    if complete(dest):
        return
    parent = os.path.dirname(dest)
    os.makedirs(parent, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=parent, prefix=".mujoco-fetch-") as workdir:
        wheel = download(workdir)
        check_hash(wheel)
        staging = os.path.join(workdir, "staging")
        extract(wheel, staging)
        if os.path.exists(dest):
            shutil.rmtree(dest)
        try:
            os.rename(staging, dest)
        except OSError:
            if not complete(dest):  # another build finished first, otherwise a real error
                raise
    sys.stderr.write(f"MuJoCo {VERSION} fetched into {dest}\n")


if __name__ == "__main__":
    main()
