"""Reads a ROS 2 MCAP recording with one of two third-party ROS 2 readers, run as a separate
process: `rosbags` (its own MCAP reader and CDR deserialiser, from the message definitions in
the file) or `mcap-ros2-support` (the `mcap` reader with its ROS 2 decoder), to check that
yarok's `ros2` profile opens in the ROS 2 tools.

Usage: ros2_bag_read.py rosbags|mcap_ros2 FILE
Prints, a line each:
  `profile NAME` (mcap_ros2: the MCAP header's; rosbags refuses files whose profile is not ros2);
  `channel_metadata TOPIC KEY=VALUE...` (mcap_ros2) for every channel with metadata;
  `topic NAME TYPE COUNT` for every topic;
  `joint_names NAME...`, then `joint_state TIME POSITION...` for every /joint_states message;
  `image TOPIC TIME WIDTH HEIGHT MODE SPREAD` for every sensor_msgs/msg/CompressedImage, decoded
  by Pillow (SPREAD: its brightest less its darkest value);
  `depth TOPIC TIME WIDTH HEIGHT NEAREST FARTHEST` for every 32FC1 sensor_msgs/msg/Image;
  `transforms COUNT FRAME` for the last /tf message (its transforms, the first's parent frame);
  `clock TIME` for every /clock message, `log TIME LEVEL TEXT` for every /log message.
"""

import io
import sys
from collections import Counter
from pathlib import Path

import numpy
from PIL import Image


def seconds(stamp):
    return stamp.sec + stamp.nanosec * 1e-9


def rosbags_messages(path):
    from rosbags.highlevel import AnyReader

    with AnyReader([Path(path)]) as reader:
        print("profile ros2")
        for connection, _, raw in reader.messages():
            yield connection.topic, connection.msgtype, reader.deserialize(raw, connection.msgtype)


def mcap_ros2_messages(path):
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    with open(path, "rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        print("profile", reader.get_header().profile)
        summary = reader.get_summary()
        for channel in (summary.channels.values() if summary else []):
            if channel.metadata:
                print("channel_metadata", channel.topic,
                      *(f"{key}={value}" for key, value in sorted(channel.metadata.items())))
        for schema, channel, _, message in reader.iter_decoded_messages(log_time_order=True):
            yield channel.topic, schema.name, message


def main():
    reader, path = sys.argv[1], sys.argv[2]
    messages = {"rosbags": rosbags_messages, "mcap_ros2": mcap_ros2_messages}[reader](path)
    counts = Counter()
    types = {}
    names_printed = False
    last_transforms = None
    for topic, msgtype, message in messages:
        counts[topic] += 1
        types[topic] = msgtype
        if msgtype == "sensor_msgs/msg/JointState":
            if not names_printed:
                print("joint_names", *message.name)
                names_printed = True
            print("joint_state", repr(seconds(message.header.stamp)), *(repr(float(p)) for p in message.position))
        elif msgtype == "sensor_msgs/msg/CompressedImage":
            image = Image.open(io.BytesIO(bytes(message.data)))
            image.load()
            low, high = image.getextrema()[0] if image.mode == "RGB" else image.getextrema()
            print("image", topic, repr(seconds(message.header.stamp)), image.width, image.height, image.mode, high - low)
        elif msgtype == "sensor_msgs/msg/Image":
            assert message.encoding == "32FC1" and message.is_bigendian == 0, message.encoding
            assert message.step == 4 * message.width
            depth = numpy.frombuffer(bytes(message.data), dtype="<f4").reshape(message.height, message.width)
            print("depth", topic, repr(seconds(message.header.stamp)), message.width, message.height, repr(float(depth.min())), repr(float(depth.max())))
        elif msgtype == "tf2_msgs/msg/TFMessage":
            last_transforms = message.transforms
        elif msgtype == "rosgraph_msgs/msg/Clock":
            print("clock", repr(seconds(message.clock)))
        elif msgtype == "rcl_interfaces/msg/Log":
            print("log", repr(seconds(message.stamp)), message.level, message.msg)
    for topic, count in sorted(counts.items()):
        print("topic", topic, types[topic], count)
    if last_transforms is not None:
        print("transforms", len(last_transforms), last_transforms[0].header.frame_id)


if __name__ == "__main__":
    main()
