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

import zenoh_peer


def main():
    endpoint, world, path, state, command, body, field, value = sys.argv[1:9]
    refused_bodies = sys.argv[9:]
    body, value = json.loads(body), json.loads(value)
    prefix = f"yarok/{world}/{path}"
    with zenoh_peer.client(endpoint) as session:
        samples = zenoh_peer.samples_of(session, f"{prefix}/**")

        def next_sample(deadline):
            while time.monotonic() < deadline:
                try:
                    return samples.get(timeout=0.5)
                except queue.Empty:
                    continue
            return None, None

        def next_on(leaf, deadline, what):
            """The JSON of the next sample at PREFIX/leaf before `deadline`; exits if none came."""
            while True:
                key, payload = next_sample(deadline)
                if key is None:
                    sys.exit(f"no {what} came")
                if key == f"{prefix}/{leaf}":
                    return json.loads(payload)

        first = next_on(state, time.monotonic() + 20, f"{prefix}/{state}")
        print("state", json.dumps(first, sort_keys=True), flush=True)
        for refused in refused_bodies:
            session.put(f"{prefix}/{command}", refused)
            reply = next_on("reply", time.monotonic() + 20, f"reply to {refused}")
            print("refused", json.dumps(reply, sort_keys=True), flush=True)
        session.put(f"{prefix}/{command}", json.dumps(body))
        deadline = time.monotonic() + 20
        reply = next_on("reply", deadline, "reply")
        print("reply", json.dumps(reply, sort_keys=True), flush=True)
        changed = next_on(state, deadline, f"change (reply {reply})")
        while changed.get(field) != value:
            changed = next_on(state, deadline, f"change (reply {reply})")
        print("changed", json.dumps(changed, sort_keys=True), flush=True)


if __name__ == "__main__":
    main()
