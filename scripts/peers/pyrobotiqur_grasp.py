"""Drives a Robotiq gripper's URCap socket with pyrobotiqur (a third-party client, run as a
separate process), to check that yarok's fake controller answers as the URCap does.

Usage: pyrobotiqur_grasp.py HOST
Activates, closes on whatever is between the fingers, opens, and prints, a line each,
`STEP: RESULT` as pyrobotiqur returned it.
"""

import sys

from pyrobotiqur.robotiq import RobotiqGripper


def main():
    gripper = RobotiqGripper(sys.argv[1])
    gripper.connect()
    gripper.activate()
    print("status:", int(gripper.get_status()))
    position, motion = gripper.close(speed=255, force=100)
    print("closed:", position, int(motion))
    position, motion = gripper.open(speed=255)
    print("opened:", position, int(motion))
    print("fault:", gripper.get_fault(), flush=True)
    gripper.disconnect()


if __name__ == "__main__":
    main()
