"""Reads a UR controller's real-time interface (port 30003) with python-urx's real-time monitor
(a third-party client, run as a separate process), to check that yarok's fake controller
streams it as a real one does.

Usage: urx_realtime.py HOST
Prints `q: Q…`, the actual joint positions urx unpacked from the stream.
"""

import collections
import collections.abc
import sys

# math3d 3.4 (which urx needs) predates Python 3.10's removal of these aliases.
collections.Iterable = collections.abc.Iterable

import urx  # noqa: E402


def main():
    robot = urx.URRobot(sys.argv[1], use_rt=True)
    try:
        q = robot.rtmon.q_actual(wait=True)
        print("q:", *(repr(float(v)) for v in q), flush=True)
    finally:
        robot.close()


if __name__ == "__main__":
    main()
