"""What the Zenoh test peers share: a client session to one router (no scouting), and a queue
of the samples published under a key expression, as (key, payload bytes)."""

import json
import queue

import zenoh


def client(endpoint):
    """A Zenoh session in client mode, connected to `endpoint` only."""
    config = zenoh.Config()
    config.insert_json5("mode", '"client"')
    config.insert_json5("connect/endpoints", json.dumps([endpoint]))
    config.insert_json5("scouting/multicast/enabled", "false")
    return zenoh.open(config)


def samples_of(session, key_expr):
    """A queue that receives every sample published under `key_expr`."""
    samples = queue.Queue()
    session.declare_subscriber(key_expr, lambda s: samples.put((str(s.key_expr), s.payload.to_bytes())))
    return samples
