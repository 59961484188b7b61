"""Reads an MCAP recording with the `mcap` library from PyPI (a third-party reader, run as a
separate process) and decodes its images with Pillow, to check that yarok's recordings open in
others' tools.

Usage: mcap_summary.py FILE
Prints, a line each:
  `topic NAME SCHEMA ENCODING COUNT` for every channel;
  `joint_names NAME...`, then `joint_state TIME POSITION...` for every /joint_states message;
  `image TOPIC TIME WIDTH HEIGHT MODE SPREAD FRAME` for every image message, decoded (SPREAD:
  the difference between its brightest and darkest pixel values; FRAME its frame_id);
  `transforms COUNT FRAME...` for the frames in the last /tf message;
  `log TIME TEXT` for every /log message;
  `state TOPIC TIME JSON` for every yarok.State message (a component's named state, JSON
  without its timestamp, keys sorted);
  `summary CHANNELS MESSAGES` from the file's summary section (`summary none` without one: a
  file cut short);
  `metadata NAME KEY=VALUE...` for every metadata record;
  `chunks COMPRESSION...` the compression of every chunk, in the file's order.
"""

import base64
import io
import json
import sys
from collections import Counter

from mcap.reader import make_reader
from PIL import Image


def seconds(stamp):
    return stamp["sec"] + stamp["nsec"] * 1e-9


def main():
    counts = Counter()
    kinds = {}
    names_printed = False
    last_transforms = []
    with open(sys.argv[1], "rb") as stream:
        reader = make_reader(stream)
        for schema, channel, message in reader.iter_messages(log_time_order=True):
            topic = channel.topic
            counts[topic] += 1
            kinds[topic] = (schema.name if schema else "-", channel.message_encoding)
            body = json.loads(message.data)
            if topic == "/joint_states":
                if not names_printed:
                    print("joint_names", *(joint["name"] for joint in body["joints"]))
                    names_printed = True
                print("joint_state", repr(message.log_time * 1e-9), *(repr(joint["position"]) for joint in body["joints"]))
            elif schema is not None and schema.name == "foxglove.CompressedImage":
                image = Image.open(io.BytesIO(base64.b64decode(body["data"])))
                image.load()
                low, high = image.getextrema()[0] if image.mode == "RGB" else image.getextrema()
                print("image", topic, repr(seconds(body["timestamp"])), image.width, image.height, image.mode, high - low, body["frame_id"])
            elif topic == "/tf":
                last_transforms = [transform["child_frame_id"] for transform in body["transforms"]]
            elif schema is not None and schema.name == "yarok.State":
                fields = {key: value for key, value in body.items() if key != "timestamp"}
                print("state", topic, repr(seconds(body["timestamp"])), json.dumps(fields, sort_keys=True))
            elif topic == "/log":
                print("log", repr(seconds(body["timestamp"])), body["message"])
        summary = reader.get_summary()
        metadata = list(reader.iter_metadata()) if summary is not None else []
    for topic, count in sorted(counts.items()):
        schema, encoding = kinds[topic]
        print("topic", topic, schema, encoding, count)
    print("transforms", len(last_transforms), *last_transforms)
    for record in metadata:
        print("metadata", record.name, *(f"{key}={value}" for key, value in sorted(record.metadata.items())))
    print("chunks", *(chunk.compression or "none" for chunk in (summary.chunk_indexes if summary else [])))
    if summary is None or summary.statistics is None:
        print("summary none")
    else:
        print("summary", len(summary.channels), summary.statistics.message_count)


if __name__ == "__main__":
    main()
