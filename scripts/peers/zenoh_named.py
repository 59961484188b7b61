"""Talks to a component's named state and command on a yarok world's Zenoh bridge with
eclipse-zenoh (the Zenoh project's Python client, a third-party peer run as a separate process):
reads the state, sends the command, and waits for the reply and for the state to show it.

Usage: zenoh_named.py ENDPOINT WORLD PATH STATE COMMAND BODY_JSON FIELD VALUE_JSON [REFUSED_JSON…]
Each REFUSED_JSON body is sent first, one at a time, each answered before the next.
Prints, a line each: `state JSON` (the first state read), `refused JSON` (each refused body's
reply), `reply JSON`, `changed JSON` (the first state whose FIELD is VALUE after the reply), or
exits non-zero saying what did not come.
"""

import json
import queue
import sys
import time

import zenoh


def main():
    endpoint, world, path, state, command, body, field, value = sys.argv[1:9]
    refused_bodies = sys.argv[9:]
    body, value = json.loads(body), json.loads(value)
    prefix = f"yarok/{world}/{path}"
    config = zenoh.Config()
    config.insert_json5("mode", '"client"')
    config.insert_json5("connect/endpoints", json.dumps([endpoint]))
    config.insert_json5("scouting/multicast/enabled", "false")
    samples = queue.Queue()
    with zenoh.open(config) as session:
        session.declare_subscriber(f"{prefix}/**", lambda s: samples.put((str(s.key_expr), s.payload.to_bytes())))

        def next_sample(deadline):
            while time.monotonic() < deadline:
                try:
                    return samples.get(timeout=0.5)
                except queue.Empty:
                    continue
            return None, None

        deadline = time.monotonic() + 20
        first = None
        while first is None:
            key, payload = next_sample(deadline)
            if key is None:
                sys.exit(f"no {prefix}/{state} came")
            if key == f"{prefix}/{state}":
                first = json.loads(payload)
        print("state", json.dumps(first, sort_keys=True), flush=True)
        for refused in refused_bodies:
            session.put(f"{prefix}/{command}", refused)
            deadline = time.monotonic() + 20
            while True:
                key, payload = next_sample(deadline)
                if key is None:
                    sys.exit(f"no reply came to {refused}")
                if key == f"{prefix}/reply":
                    print("refused", json.dumps(json.loads(payload), sort_keys=True), flush=True)
                    break
        session.put(f"{prefix}/{command}", json.dumps(body))
        reply, changed, deadline = None, None, time.monotonic() + 20
        while changed is None:
            key, payload = next_sample(deadline)
            if key is None:
                sys.exit(f"no change came (reply {reply})")
            if key == f"{prefix}/reply":
                reply = json.loads(payload)
                print("reply", json.dumps(reply, sort_keys=True), flush=True)
            elif key == f"{prefix}/{state}" and reply is not None:
                seen = json.loads(payload)
                if seen.get(field) == value:
                    changed = seen
        print("changed", json.dumps(changed, sort_keys=True), flush=True)


if __name__ == "__main__":
    main()
