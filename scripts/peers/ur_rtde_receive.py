"""Reads a UR controller's state with ur_rtde's RTDEReceiveInterface (a third-party client, run
as a separate process), to check that yarok's fake controller answers as a real one does.

Usage: ur_rtde_receive.py HOST
Prints, a line each, `NAME VALUE...`: the joint positions (`q`), the robot and safety modes and
the controller's timestamp, as ur_rtde reads them.
"""

import sys
import time

import rtde_receive


def main():
    receive = rtde_receive.RTDEReceiveInterface(sys.argv[1])
    # The first data package may still be on its way.
    deadline = time.monotonic() + 5.0
    while receive.getTimestamp() == 0.0 and time.monotonic() < deadline:
        time.sleep(0.01)
    print("q", *(repr(v) for v in receive.getActualQ()))
    print("robot_mode", receive.getRobotMode())
    print("safety_mode", receive.getSafetyMode())
    print("timestamp", repr(receive.getTimestamp()), flush=True)
    receive.disconnect()


if __name__ == "__main__":
    main()
