"""Reads a UR controller's joints and moves them with python-urx (a third-party client over
the secondary interface, run as a separate process), to check that yarok's fake controller
answers as a CB3 controller does.

Usage: urx_movej.py HOST Q0 Q1 Q2 Q3 Q4 Q5
Prints `before: Q…`, then moves to the given joints (waiting as urx waits: for the program to
run and the arm to come within its threshold) and prints `after: Q…`.
"""

import collections
import collections.abc
import sys

# math3d 3.4 (which urx needs) predates Python 3.10's removal of these aliases.
collections.Iterable = collections.abc.Iterable

import urx  # noqa: E402


def main():
    robot = urx.URRobot(sys.argv[1])
    try:
        print("before:", *(repr(q) for q in robot.getj()), flush=True)
        target = [float(q) for q in sys.argv[2:8]]
        robot.movej(target, acc=1.0, vel=1.0, wait=True)
        print("after:", *(repr(q) for q in robot.getj()), flush=True)
        print("running:", robot.is_running(), flush=True)
    finally:
        robot.close()


if __name__ == "__main__":
    main()
