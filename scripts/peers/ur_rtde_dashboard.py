"""Drives a UR controller's dashboard server with ur_rtde's DashboardClient (a third-party
client, run as a separate process), to check that yarok's fake controller answers as a real
one does.

Usage: ur_rtde_dashboard.py HOST
Prints, a line each, `STEP: RESULT` — what the client returned, or `error: …` when it raised.
"""

import sys

import dashboard_client


def main():
    dashboard = dashboard_client.DashboardClient(sys.argv[1])
    dashboard.connect()

    def step(name, call):
        try:
            result = call()
        except RuntimeError as error:
            result = f"error: {error}"
        print(f"{name}: {result}", flush=True)

    step("version", dashboard.polyscopeVersion)
    step("mode before", dashboard.robotmode)
    step("power on", dashboard.powerOn)
    step("brake release", dashboard.brakeRelease)
    step("mode after", dashboard.robotmode)
    step("safety", dashboard.safetymode)
    step("unlock", dashboard.unlockProtectiveStop)
    step("safety after", dashboard.safetymode)
    step("close popup", dashboard.closeSafetyPopup)
    step("load", lambda: dashboard.loadURP("pick.urp"))
    step("play", dashboard.play)
    step("stop", dashboard.stop)
    dashboard.disconnect()


if __name__ == "__main__":
    main()
