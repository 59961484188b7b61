"""Writes a UR controller's outputs and registers with ur_rtde's RTDEIOInterface (a third-party
client, run as a separate process), to check that yarok's fake controller takes its input
recipes as a real one does.

Usage: ur_rtde_io.py HOST
Sets standard digital output 2, the speed slider to 0.5 and input double register 18 to 0.25,
then prints `done`.
"""

import sys

import rtde_io


def main():
    io = rtde_io.RTDEIOInterface(sys.argv[1])
    io.setStandardDigitalOut(2, True)
    io.setSpeedSlider(0.5)
    io.setInputDoubleRegister(18, 0.25)
    io.disconnect()
    print("done", flush=True)


if __name__ == "__main__":
    main()
