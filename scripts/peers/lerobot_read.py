"""Reads a LeRobot v3 dataset as LeRobot does, as a separate process with third-party readers
written from LeRobot's own code (lerobot/datasets/utils.py, io_utils.py, dataset_metadata.py,
dataset_writer.py, compute_stats.py): pyarrow reads the Parquet tables, pandas the tasks, PyAV
decodes every video frame, numpy recomputes the statistics.

Usage: lerobot_read.py DATASET [MCAP...]
With MCAP files (one per episode, in order; recorded with images at the dataset's fps), every
video frame is compared with the image the recording holds of the same tick.

Prints, a line each:
  `episodes N frames N tasks N fps N`;
  `episode I length N tasks TASK|TASK`;
  `video KEY frames N codec C pix_fmt P` per video feature, over every episode;
  `states N equal to the recording's (joints J)`, with MCAP files: the frames whose
  `observation.state` equals, bit for bit as 32-bit floats, the joint positions recorded at
  their tick (where the recording has joint states at that tick), over the J elements named as
  recorded joints;
  `matched KEY frames N min_psnr DB own DB next DB` per video feature, with MCAP files: the
  lowest PSNR of a frame against its recorded image, and the mean PSNR of the frames against
  their own recorded image and against the next one (a frame one off would score the second);
  `stats FEATURE ok` per feature, once its statistics equal the recomputed ones;
  `start I FEATURE NAME=VALUE ...` and `end I FEATURE NAME=VALUE ...` per episode and vector
  feature: the episode's first and last frames, element by element as the feature names them.
Exits non-zero naming the file, the episode, the feature and the rule when anything fails.
"""

import base64
import io
import json
import sys
from pathlib import Path

import av
import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
from mcap.reader import make_reader
from PIL import Image

QUANTILES = {"q01": 0.01, "q10": 0.10, "q50": 0.50, "q90": 0.90, "q99": 0.99}
# LeRobot's `check_timestamps_sync` tolerance.
TOLERANCE_S = 1e-4
INDEX_DTYPES = {"timestamp": "float", "frame_index": "int64", "episode_index": "int64",
                "index": "int64", "task_index": "int64"}


def fail(text):
    sys.exit(f"lerobot_read: {text}")


def expect(condition, text):
    if not condition:
        fail(text)


def read_info(root):
    info = json.loads((root / "meta/info.json").read_text())
    expect(info["codebase_version"] == "v3.0", f"codebase_version {info['codebase_version']}")
    for key in ["fps", "features", "total_episodes", "total_frames", "total_tasks",
                "chunks_size", "data_path", "splits", "robot_type"]:
        expect(key in info, f"info.json has no {key}")
    for name in INDEX_DTYPES:
        expect(name in info["features"], f"info.json's features have no {name}")
    expect(info["splits"] == {"train": f"0:{info['total_episodes']}"}, f"splits {info['splits']}")
    return info


def read_tasks(root, info):
    tasks = pd.read_parquet(root / "meta/tasks.parquet")
    expect(tasks.index.name == "task", f"tasks.parquet is indexed by {tasks.index.name!r}, not task")
    expect(list(tasks["task_index"]) == list(range(len(tasks))), "task_index is not 0..n")
    expect(len(tasks) == info["total_tasks"], f"{len(tasks)} tasks, info says {info['total_tasks']}")
    return {int(row.task_index): task for task, row in tasks.iterrows()}


def read_episodes(root, info):
    paths = sorted((root / "meta/episodes").glob("*/*.parquet"))
    expect(paths, "no meta/episodes/*/*.parquet")
    episodes = pq.read_table(paths).to_pylist()
    expect(len(episodes) == info["total_episodes"],
           f"{len(episodes)} episode rows, info says {info['total_episodes']}")
    start = 0
    for number, episode in enumerate(episodes):
        where = f"episode {number}"
        expect(episode["episode_index"] == number, f"{where}: episode_index {episode['episode_index']}")
        expect(episode["dataset_from_index"] == start, f"{where}: from {episode['dataset_from_index']}")
        expect(episode["dataset_to_index"] - start == episode["length"], f"{where}: to - from != length")
        start = episode["dataset_to_index"]
    expect(start == info["total_frames"], f"episodes hold {start} frames, info says {info['total_frames']}")
    return episodes


def read_data(root, info, episodes):
    files = sorted({(e["data/chunk_index"], e["data/file_index"]) for e in episodes})
    tables = []
    for chunk, file in files:
        path = root / info["data_path"].format(chunk_index=chunk, file_index=file)
        expect(path.is_file(), f"no {path}")
        tables.append(pq.read_table(path))
    schema = tables[0].schema
    for name, feature in info["features"].items():
        if feature["dtype"] == "video":
            expect(name not in schema.names, f"video feature {name} is a data column")
            continue
        expect(name in schema.names, f"the data has no column {name}")
        kind = schema.field(name).type
        shape = feature["shape"]
        if shape == [1]:
            expected = INDEX_DTYPES.get(name, feature["dtype"])
            expect(str(kind) == expected, f"{name} is {kind}, not {expected}")
        else:
            # A datasets Sequence of known length: Arrow's fixed-size list.
            expect(str(kind) == f"fixed_size_list<item: {'float' if feature['dtype'] == 'float32' else feature['dtype']}>[{shape[0]}]",
                   f"{name} is {kind}, not a fixed-size list of {shape[0]} {feature['dtype']}")
            expect(len(feature["names"]) == shape[0], f"{name} has {len(feature['names'])} names")
    table = pa.concat_tables(tables)
    columns = {name: table.column(name).to_numpy() if table.schema.field(name).type.num_fields == 0
               else np.stack(table.column(name).to_pylist()).astype(np.float32)
               for name in table.schema.names}
    expect(len(table) == info["total_frames"], f"{len(table)} rows, info says {info['total_frames']}")
    expect((columns["index"] == np.arange(len(table))).all(), "index is not 0..total_frames")
    fps = info["fps"]
    for episode in episodes:
        number = episode["episode_index"]
        rows = slice(episode["dataset_from_index"], episode["dataset_to_index"])
        where = f"episode {number}"
        expect((columns["episode_index"][rows] == number).all(), f"{where}: episode_index of its rows")
        frame_index = columns["frame_index"][rows]
        expect((frame_index == np.arange(episode["length"])).all(), f"{where}: frame_index is not 0..length")
        timestamps = columns["timestamp"][rows]
        expect(np.allclose(timestamps, frame_index / fps, atol=TOLERANCE_S, rtol=0),
               f"{where}: timestamps are not frame_index / fps")
        if len(timestamps) > 1:
            expect(np.allclose(np.diff(timestamps), 1 / fps, atol=TOLERANCE_S, rtol=0),
                   f"{where}: timestamps are not 1/{fps} s apart")
    return columns


def decode(path):
    """Every frame of the video at `path`, RGB, with its time and the stream's facts."""
    with av.open(str(path)) as container:
        stream = container.streams.video[0]
        facts = (stream.codec_context.name, stream.codec_context.format.name,
                 stream.width, stream.height, float(stream.average_rate))
        frames = [(float(frame.pts * stream.time_base), frame.to_ndarray(format="rgb24"))
                  for frame in container.decode(stream)]
    return frames, facts


def recorded_images(mcap_path, key):
    """The images of a video feature's probe in a yarok MCAP recording, in order."""
    # A probe's topic is its path (`/arm/left/image`), a model camera's `/cameras/{name}`.
    path = "/" + key.removeprefix("observation.images.").replace(".", "/")
    topics = [path, "/cameras" + path]
    images = []
    with open(mcap_path, "rb") as file:
        for _, channel, message in make_reader(file).iter_messages(topics=topics):
            data = json.loads(message.data)["data"]
            images.append(np.asarray(Image.open(io.BytesIO(base64.b64decode(data))).convert("RGB")))
    expect(images, f"{mcap_path} has no images on {' or '.join(topics)}")
    return images


def recorded_states(mcap_path, names):
    """Joint positions a yarok MCAP recording holds (`/joint_states`), by log time, of those of
    `names` it records (in `names`' order), and which of `names` those are."""
    states, image_times, recorded = {}, [], None
    with open(mcap_path, "rb") as file:
        for _, channel, message in make_reader(file).iter_messages():
            if channel.topic == "/joint_states":
                joints = {j["name"]: j["position"] for j in json.loads(message.data)["joints"]}
                if recorded is None:
                    recorded = [name for name in names if name in joints]
                states[message.log_time] = [joints[name] for name in recorded]
            elif channel.topic.endswith("/image") or channel.topic.startswith("/cameras/"):
                # The ticks images were taken at: the dataset's frames'.
                image_times.append(message.log_time)
    return states, sorted(set(image_times)), recorded or []


def check_states(mcap_path, info, columns, episode):
    """Every frame's `observation.state` against the positions recorded at its tick, bit for bit
    as 32-bit floats, element by element where the recording has a joint of the element's name
    (a gripper's measured position is no joint); the number of frames checked, and of elements
    compared in each."""
    names = info["features"]["observation.state"]["names"]
    states, image_times, recorded = recorded_states(mcap_path, names)
    if not recorded:
        return 0, 0
    elements = [names.index(name) for name in recorded]
    rows = columns["observation.state"][episode["dataset_from_index"]:episode["dataset_to_index"]]
    rows = rows[:, elements]
    expect(len(image_times) == len(rows), f"{mcap_path}: {len(image_times)} image times for {len(rows)} frames")
    checked = 0
    for number, (time, row) in enumerate(zip(image_times, rows)):
        if time not in states:
            continue
        want = np.asarray(states[time], dtype=np.float32)
        expect(np.array_equal(row, want), f"episode {episode['episode_index']}, frame {number}: "
               f"observation.state {row} is not the recorded {want}")
        checked += 1
    return checked, len(recorded)


def psnr(a, b):
    mse = np.mean((a.astype(np.float64) - b.astype(np.float64)) ** 2)
    return 100.0 if mse == 0 else min(100.0, 10 * np.log10(255.0**2 / mse))


def check_stats(name, got, values, image, where):
    """`got` (LeRobot's stats of `name`) against `values` (samples × elements, or for an image
    the frames' pixels: frames × height × width × channels)."""
    if image:
        pixels = values.reshape(-1, 3).astype(np.float64) / 255.0
        expected = {"min": pixels.min(0), "max": pixels.max(0), "mean": pixels.mean(0),
                    "std": pixels.std(0)} | {k: np.quantile(pixels, q, axis=0) for k, q in QUANTILES.items()}
        # The video is lossy: its pixels are the recorded ones to within a few levels.
        for key, want in expected.items():
            have = np.asarray(got[key], dtype=np.float64)
            expect(have.shape == (3, 1, 1), f"{where}: {name}'s {key} has shape {have.shape}, not (3, 1, 1)")
            tolerance = 0.02 if key in ("mean", "std") else 0.08
            expect(np.allclose(have.reshape(3), want, atol=tolerance),
                   f"{where}: {name}'s {key} {have.reshape(3)} is not the decoded frames' {want}")
        expect(list(got["count"]) == [len(values)], f"{where}: {name}'s count {got['count']}")
        return
    values = values.astype(np.float64).reshape(len(values), -1)
    expected = {"min": values.min(0), "max": values.max(0), "mean": values.mean(0),
                "std": values.std(0)} | {k: np.quantile(values, q, axis=0) for k, q in QUANTILES.items()}
    for key, want in expected.items():
        have = np.asarray(got[key], dtype=np.float64)
        expect(have.shape == want.shape, f"{where}: {name}'s {key} has shape {have.shape}, not {want.shape}")
        expect(np.allclose(have, want, rtol=1e-6, atol=1e-9),
               f"{where}: {name}'s {key} {have} is not the data's {want}")
    expect(list(got["count"]) == [len(values)], f"{where}: {name}'s count {got['count']}, not {len(values)}")


def episode_stats(episode, name):
    prefix = f"stats/{name}/"
    return {key.removeprefix(prefix): value for key, value in episode.items() if key.startswith(prefix)}


def main():
    root = Path(sys.argv[1])
    mcaps = [Path(p) for p in sys.argv[2:]]
    info = read_info(root)
    tasks = read_tasks(root, info)
    episodes = read_episodes(root, info)
    columns = read_data(root, info, episodes)
    fps = info["fps"]
    print(f"episodes {len(episodes)} frames {info['total_frames']} tasks {len(tasks)} fps {fps}")
    for episode in episodes:
        rows = slice(episode["dataset_from_index"], episode["dataset_to_index"])
        used = [tasks[int(t)] for t in dict.fromkeys(columns["task_index"][rows])]
        expect(used == episode["tasks"], f"episode {episode['episode_index']}: tasks {episode['tasks']}, frames' {used}")
        print(f"episode {episode['episode_index']} length {episode['length']} tasks {'|'.join(used)}")
    for episode in episodes:
        for name, feature in info["features"].items():
            if feature["dtype"] == "float32" and feature.get("names") and name in columns:
                for end, row in (("start", episode["dataset_from_index"]), ("end", episode["dataset_to_index"] - 1)):
                    values = np.asarray(columns[name][row], dtype=np.float64)
                    print(f"{end} {episode['episode_index']} {name} "
                          + " ".join(f"{n}={v:.6f}" for n, v in zip(feature["names"], values)))
    if mcaps:
        expect(len(mcaps) == len(episodes), f"{len(mcaps)} recordings for {len(episodes)} episodes")
        results = [check_states(mcap, info, columns, episode) for mcap, episode in zip(mcaps, episodes)]
        checked = sum(frames for frames, _ in results)
        joints = results[0][1]
        print(f"states {checked} equal to the recording's (joints {joints})")
    stats_json = json.loads((root / "meta/stats.json").read_text())
    all_pixels = {}
    for name, feature in info["features"].items():
        if feature["dtype"] != "video":
            continue
        height, width, channels = feature["shape"]
        decoded_frames, worst, own, shifted = 0, float("inf"), [], []
        pixels = []
        for number, episode in enumerate(episodes):
            where = f"episode {number}, {name}"
            path = root / info["video_path"].format(
                video_key=name, chunk_index=episode[f"videos/{name}/chunk_index"],
                file_index=episode[f"videos/{name}/file_index"])
            expect(path.is_file(), f"{where}: no {path}")
            frames, (codec, pix_fmt, w, h, rate) = decode(path)
            expect((codec, pix_fmt) == (feature["info"]["video.codec"], feature["info"]["video.pix_fmt"]),
                   f"{where}: {codec}/{pix_fmt}, info says {feature['info']['video.codec']}/{feature['info']['video.pix_fmt']}")
            expect((w, h) == (width, height), f"{where}: {w}×{h}, shape says {width}×{height}")
            expect(abs(rate - fps) < 1e-6, f"{where}: {rate} fps, not {fps}")
            expect(len(frames) == episode["length"], f"{where}: {len(frames)} frames for {episode['length']} rows")
            start = episode[f"videos/{name}/from_timestamp"]
            expect(abs(episode[f"videos/{name}/to_timestamp"] - start - episode["length"] / fps) < TOLERANCE_S,
                   f"{where}: from/to timestamps do not span its frames")
            rows = slice(episode["dataset_from_index"], episode["dataset_to_index"])
            for (time, _), timestamp in zip(frames, columns["timestamp"][rows]):
                # LeRobot's decoder takes the frame nearest `from_timestamp + timestamp`.
                expect(abs(time - (start + timestamp)) < TOLERANCE_S, f"{where}: a frame at {time} s for timestamp {timestamp}")
            images = np.stack([image for _, image in frames])
            check_stats(name, episode_stats(episode, name), images, True, where)
            pixels.append(images)
            decoded_frames += len(frames)
            if mcaps:
                recorded = recorded_images(mcaps[number], name)
                expect(len(recorded) == len(frames),
                       f"{where}: {len(frames)} video frames, {len(recorded)} recorded images in {mcaps[number]}")
                for index, (image, (_, frame)) in enumerate(zip(recorded, frames)):
                    score = psnr(image, frame)
                    expect(score >= 35, f"{where}: frame {index} is {score:.1f} dB from the recorded image")
                    worst = min(worst, score)
                    own.append(score)
                    if index + 1 < len(recorded):
                        shifted.append(psnr(recorded[index + 1], frame))
        all_pixels[name] = np.concatenate(pixels)
        print(f"video {name} frames {decoded_frames} codec {codec} pix_fmt {pix_fmt}")
        if mcaps:
            print(f"matched {name} frames {decoded_frames} min_psnr {worst:.1f} "
                  f"own {np.mean(own):.2f} next {np.mean(shifted):.2f}")
    for name, feature in info["features"].items():
        if feature["dtype"] == "video":
            check_stats(name, stats_json[name], all_pixels[name], True, "stats.json")
        else:
            for episode in episodes:
                rows = slice(episode["dataset_from_index"], episode["dataset_to_index"])
                check_stats(name, episode_stats(episode, name), columns[name][rows], False,
                            f"episode {episode['episode_index']}")
            check_stats(name, stats_json[name], columns[name], False, "stats.json")
        print(f"stats {name} ok")


if __name__ == "__main__":
    main()
