"""Talks to a yarok world's Zenoh bridge with eclipse-zenoh (the Zenoh project's Python client,
a third-party peer run as a separate process): reads the world's joint states, its arm's state
and a probe image (decoded with Pillow), then commands the arm to joints and waits until it is
there, and sends its gripper positions outside 0-255.

Usage: zenoh_client.py ENDPOINT WORLD TARGET_JOINTS_JSON
Prints, a line each: `joint_states COUNT NAMES`, `arm_q Q...`, `image KEY WIDTH HEIGHT`,
`reply JSON`, `reached SECONDS Q...`, `gripper_reply_POSITION JSON` for positions 256, -1
and 1.5, `huge_reply JSON` for a command of a megabyte (or exits non-zero saying what did not come).
"""

import io
import json
import queue
import sys
import time

from PIL import Image

import zenoh_peer


def main():
    endpoint, world, target = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
    with zenoh_peer.client(endpoint) as session:
        samples = zenoh_peer.samples_of(session, f"yarok/{world}/**")
        joint_states, arm, image, deadline = 0, None, None, time.monotonic() + 20
        names = None
        while (joint_states < 5 or arm is None or image is None) and time.monotonic() < deadline:
            try:
                key, payload = samples.get(timeout=0.5)
            except queue.Empty:
                continue
            if key.endswith("/joint_states"):
                joint_states += 1
                names = [joint["name"] for joint in json.loads(payload)["joints"]]
            elif key == f"yarok/{world}/arm/state":
                arm = json.loads(payload)
            elif key.endswith("/image"):
                decoded = Image.open(io.BytesIO(payload))
                decoded.load()
                image = (key, decoded.width, decoded.height)
        if joint_states < 5 or arm is None or image is None:
            sys.exit(f"not all came: {joint_states} joint states, arm {arm is not None}, image {image}")
        print("joint_states", joint_states, " ".join(names[:6]))
        print("arm_q", *arm["q"])
        print("image", *image)
        started = time.monotonic()
        session.put(f"yarok/{world}/arm/command", json.dumps({"move_j": target, "speed": 2.0, "acceleration": 4.0}))
        reply, reached = None, None
        while reached is None and time.monotonic() < started + 30:
            try:
                key, payload = samples.get(timeout=0.5)
            except queue.Empty:
                continue
            if key == f"yarok/{world}/arm/reply":
                reply = json.loads(payload)
                print("reply", json.dumps(reply), flush=True)
            elif key == f"yarok/{world}/arm/state" and reply is not None:
                q = json.loads(payload)["q"]
                if max(abs(a - b) for a, b in zip(q, target)) < 0.01:
                    reached = (time.monotonic() - started, q)
        if reached is None:
            sys.exit(f"the arm did not reach {target} (reply {reply})")
        print("reached", f"{reached[0]:.2f}", *reached[1])
        for position in (256, -1, 1.5):
            session.put(f"yarok/{world}/arm/gripper/command", json.dumps({"move_to": position}))
            reply, deadline = None, time.monotonic() + 10
            while reply is None and time.monotonic() < deadline:
                try:
                    key, payload = samples.get(timeout=0.5)
                except queue.Empty:
                    continue
                if key == f"yarok/{world}/arm/gripper/reply":
                    reply = json.loads(payload)
            print(f"gripper_reply_{position}", json.dumps(reply), flush=True)
        # A command of a megabyte: refused unread, but answered.
        huge = json.dumps({"move_to": 1, "padding": "x" * 1_000_000})
        session.put(f"yarok/{world}/arm/gripper/command", huge)
        reply, deadline = None, time.monotonic() + 10
        while reply is None and time.monotonic() < deadline:
            try:
                key, payload = samples.get(timeout=0.5)
            except queue.Empty:
                continue
            if key == f"yarok/{world}/arm/gripper/reply":
                reply = json.loads(payload)
        print("huge_reply", json.dumps(reply), flush=True)
        session.put(f"yarok/{world}/command", json.dumps({"stop": True}))


if __name__ == "__main__":
    main()
