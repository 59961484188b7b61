"""Checks a `foxglove`-profile MCAP recording the way Foxglove's tools take it, as a separate
process with third-party readers: the `mcap` reader (PyPI) reads it, `jsonschema` (PyPI)
validates every message against its channel's own schema and, for Foxglove's message types,
against Foxglove's published schema of the same name (@foxglove/schemas, from npm, written out
as files by scripts/setup-test-peers.sh; yarok's own `yarok.State` has none), and every channel's schema is checked against the rules by which
the open-source Foxglove Studio and Lichtblick turn a JSON Schema into fields
(packages/mcap-support/src/parseJsonSchema.ts there): no `$ref`, every field typed, objects
with properties, strings base64 or plain, arrays of typed items.

Usage: foxglove_validate.py FILE FOXGLOVE_SCHEMAS_DIR
Prints, a line each:
  `channel TOPIC SCHEMA COUNT` for every channel, once all its messages validated;
  `frames FRAME...` the child frames of the last /tf message;
  `image_frame TOPIC FRAME` for every image channel;
  `depth TOPIC ENCODING WIDTH HEIGHT STEP UNIT NEAREST FARTHEST` for every foxglove.RawImage,
    NEAREST and FARTHEST in metres: counts (16UC1, little-endian, 0 for none) times the unit
    its channel's metadata states under `depth_unit_m`;
  `chunks COUNT COMPRESSION...` the distinct compressions of the file's chunks.
Exits non-zero naming the channel, the message and the rule when anything fails.
"""

import base64
import json
import sys
from collections import Counter
from pathlib import Path

import jsonschema
import numpy
from mcap.reader import make_reader

FIELD_TYPES = {"boolean", "string", "number", "integer", "object", "array"}
ITEM_TYPES = {"boolean", "string", "number", "integer", "object"}


def fail(text):
    sys.exit(f"foxglove_validate: {text}")


def refs(node, path="#"):
    """Every `$ref` in a schema, by where it is."""
    if isinstance(node, dict):
        for key, value in node.items():
            if key == "$ref":
                yield path
            yield from refs(value, f"{path}/{key}")
    elif isinstance(node, list):
        for index, value in enumerate(node):
            yield from refs(value, f"{path}/{index}")


def check_parseable(schema, where):
    """The field rules of Studio's and Lichtblick's JSON Schema parser, restated."""
    if schema.get("type") != "object":
        fail(f"{where}: expected \"type\": \"object\", got {schema.get('type')!r}")
    properties = schema.get("properties")
    if not isinstance(properties, dict):
        fail(f"{where}: an object without properties")
    for name, field in properties.items():
        kind = field.get("type")
        if kind not in FIELD_TYPES:
            fail(f"{where}.{name}: unsupported field type {kind!r}")
        if kind == "string" and field.get("contentEncoding") not in (None, "base64"):
            fail(f"{where}.{name}: unsupported contentEncoding {field['contentEncoding']!r}")
        if kind == "object":
            check_parseable(field, f"{where}.{name}")
        if kind == "array":
            items = field.get("items", {})
            if items.get("type") not in ITEM_TYPES:
                fail(f"{where}.{name}: unsupported array item type {items.get('type')!r}")
            if items.get("type") == "string" and "contentEncoding" in items:
                fail(f"{where}.{name}: contentEncoding on array items")
            if items.get("type") == "object":
                check_parseable(items, f"{where}.{name}")


def base64_fields(schema, value, where):
    """Decodes every base64 field of `value`, as the parser's post-processing does."""
    for name, field in schema.get("properties", {}).items():
        if name not in value:
            continue
        if field.get("contentEncoding") == "base64":
            try:
                base64.b64decode(value[name], validate=True)
            except ValueError as error:
                fail(f"{where}.{name}: not base64: {error}")
        elif field.get("type") == "object":
            base64_fields(field, value[name], f"{where}.{name}")
        elif field.get("type") == "array" and field["items"].get("type") == "object":
            for index, item in enumerate(value[name]):
                base64_fields(field["items"], item, f"{where}.{name}[{index}]")


def print_depth(channel, body):
    unit = float(channel.metadata["depth_unit_m"])
    if body["encoding"] != "16UC1":
        fail(f"{channel.topic}: depth encoded {body['encoding']}")
    data = base64.b64decode(body["data"])
    if len(data) != body["step"] * body["height"]:
        fail(f"{channel.topic}: {len(data)} bytes for {body['height']} rows of {body['step']}")
    counts = numpy.frombuffer(data, dtype="<u2").reshape(body["height"], body["step"] // 2)
    seen = counts[:, : body["width"]][counts[:, : body["width"]] > 0] * unit
    print("depth", channel.topic, body["encoding"], body["width"], body["height"], body["step"],
          repr(unit), repr(float(seen.min())), repr(float(seen.max())))


def main():
    path, published_dir = sys.argv[1], Path(sys.argv[2])
    counts = Counter()
    validators = {}
    last_frames = []
    image_frames = {}
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        summary = reader.get_summary()
        if summary is None:
            fail("no summary section")
        for channel in summary.channels.values():
            schema_record = summary.schemas[channel.schema_id]
            where = f"channel {channel.topic} ({schema_record.name})"
            if schema_record.encoding != "jsonschema" or channel.message_encoding != "json":
                fail(f"{where}: encodings {schema_record.encoding}/{channel.message_encoding}")
            schema = json.loads(schema_record.data)
            for ref in refs(schema):
                fail(f"{where}: $ref at {ref}")
            check_parseable(schema, schema_record.name)
            theirs = None
            if schema_record.name.startswith("foxglove."):
                published_file = published_dir / f"{schema_record.name}.json"
                if not published_file.is_file():
                    fail(f"{where}: Foxglove publishes no schema {schema_record.name}")
                published = json.loads(published_file.read_text())
                theirs = jsonschema.Draft202012Validator(published)
            elif not schema_record.name.startswith("yarok."):
                fail(f"{where}: a schema neither Foxglove's nor yarok's own")
            validators[channel.id] = (schema, jsonschema.Draft202012Validator(schema), theirs)
        for _, channel, message in reader.iter_messages():
            schema, own, theirs = validators[channel.id]
            where = f"{channel.topic} message {message.sequence}"
            body = json.loads(message.data)
            for name, validator in (("its own schema", own), ("Foxglove's schema", theirs)):
                if validator is None:
                    continue
                error = jsonschema.exceptions.best_match(validator.iter_errors(body))
                if error is not None:
                    fail(f"{where} against {name}: {error.message} at {list(error.absolute_path)}")
            base64_fields(schema, body, where)
            counts[channel.id] += 1
            if schema.get("title") == "foxglove.RawImage":
                print_depth(channel, body)
            if channel.topic == "/tf":
                last_frames = [t["child_frame_id"] for t in body["transforms"]]
            elif "frame_id" in body:
                image_frames[channel.topic] = body["frame_id"]
    for channel in sorted(summary.channels.values(), key=lambda c: c.topic):
        name = summary.schemas[channel.schema_id].name
        print("channel", channel.topic, name, counts[channel.id])
    print("frames", *last_frames)
    for topic, frame in sorted(image_frames.items()):
        print("image_frame", topic, frame)
    compressions = sorted({chunk.compression or "none" for chunk in summary.chunk_indexes})
    print("chunks", len(summary.chunk_indexes), *compressions)


if __name__ == "__main__":
    main()
