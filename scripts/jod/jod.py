#!/usr/bin/env python3
"""Scores the screen videos of `steadyray bench --clock real --video DIR` with ColorVideoVDP.

Each run's screen at every refresh (DIR/<run>/displayed/) is compared with the reference at
every refresh (DIR/reference/) under the viewing set-up the bench states in DIR/video.json:
ColorVideoVDP's display photometry of that name (`standard_fhd`: 200 cd/m^2, office light)
and its size and distance, with the frames filling the display (the video's pixels are the
display's area divided evenly, which is what upscaling them to the panel shows). The result
is in JOD units: 10 means indistinguishable from the reference; higher is better.

The videos are scored from the first refresh at which every run of the folder shows one of
its own frames: before it a run's screen shows the bench's last warm-up frame (held, or warped
with --warp), a start the runs do not share and that a viewer of the run would not see
(--include-lead-in scores from refresh 0, as before 2026-12-04).

Writes DIR/jod.json and, with --summary, merges the scores into the bench's summary.json and
table.md through `steadyray jod merge` (the merge is the project's Rust code, tested in CI
without Python).

    pip install -r scripts/jod/requirements.txt
    python scripts/jod/jod.py results/video --summary results/bench/summary.json
"""

import argparse
import json
import os
import shutil
import subprocess
import sys
import time
from importlib.metadata import version

import numpy as np
import torch
from PIL import Image

import pycvvdp
from pycvvdp.display_model import vvdp_display_geometry
from pycvvdp.video_source import numpy2torch_frame, video_source_dm


class PngSequence(video_source_dm):
    """Test and reference frames from two folders of frame_00000.png, ... (8-bit sRGB), read
    one at a time (a run's video does not fit in memory as floats)."""

    def __init__(self, test_dir, reference_dir, frames, fps, display_photometry):
        """`frames`: the refreshes scored (a range), in order."""
        super().__init__(display_photometry=display_photometry)
        self.test_dir, self.reference_dir = test_dir, reference_dir
        self.frames, self.fps = frames, fps
        first = self._load(reference_dir, frames[0])
        self.size = (first.shape[0], first.shape[1], len(frames))

    @staticmethod
    def _load(folder, i):
        path = os.path.join(folder, f"frame_{i:05d}.png")
        return np.asarray(Image.open(path).convert("RGB"))

    def get_video_size(self):
        return self.size

    def get_frames_per_second(self):
        return self.fps

    def _frame(self, folder, i, device, colorspace):
        img = numpy2torch_frame(self._load(folder, i), 0, device)
        return self.apply_dm_and_color_transform(img, colorspace)

    def get_test_frame(self, frame, device, colorspace="Y"):
        return self._frame(self.test_dir, self.frames[frame], device, colorspace)

    def get_reference_frame(self, frame, device, colorspace="Y"):
        return self._frame(self.reference_dir, self.frames[frame], device, colorspace)


def lead_in_refreshes(run_dir):
    """The refreshes at the start of a run's video that show the last warm-up frame (its
    timings.csv: refresh, time, frame, ...; the frame is `warmup` there)."""
    path = os.path.join(run_dir, "timings.csv")
    if not os.path.isfile(path):
        sys.exit(f"{path} is missing: not a finished `bench --video` folder")
    with open(path) as f:
        rows = [line.strip().split(",") for line in f.readlines()[1:] if line.strip()]
    count = 0
    for row in rows:
        if len(row) < 3:
            sys.exit(f"{path}: a row without a frame column: {','.join(row)}")
        if row[2] != "warmup":
            break
        count += 1
    if count == len(rows):
        sys.exit(f"{path}: no refresh shows one of the run's frames")
    return count


def find_steadyray(given):
    """The steadyray binary: --steadyray, else on PATH, else the repository's release build."""
    if given:
        return given
    on_path = shutil.which("steadyray")
    if on_path:
        return on_path
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    return os.path.join(repo, "target", "release", "steadyray")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("video_dir", help="the folder of `steadyray bench --video DIR`")
    parser.add_argument("--summary", help="the bench's summary.json to merge the scores into")
    parser.add_argument("--runs", nargs="*", help="score only these runs (names as in video.json)")
    parser.add_argument("--device", default="cuda" if torch.cuda.is_available() else "cpu")
    parser.add_argument("--steadyray", help="the steadyray binary for the merge")
    parser.add_argument("--include-lead-in", action="store_true",
                        help="score from refresh 0, the warm-up frame's refreshes included")
    args = parser.parse_args()

    index_path = os.path.join(args.video_dir, "video.json")
    if not os.path.isfile(index_path):
        sys.exit(f"{index_path} is missing: not a finished `bench --video` folder")
    with open(index_path) as f:
        index = json.load(f)
    viewing = index["viewing"]
    width, height = index["resolution"]
    geometry = vvdp_display_geometry(
        [width, height],
        distance_m=viewing["distance_m"],
        diagonal_size_inches=viewing["diagonal_in"],
    )
    device = torch.device(args.device)
    metric = pycvvdp.cvvdp(
        display_name=viewing["name"], display_geometry=geometry, device=device, quiet=True
    )
    reference_dir = os.path.join(args.video_dir, "reference")
    runs = [r for r in index["runs"] if not args.runs or r["name"] in args.runs]
    if args.runs and len(runs) != len(args.runs):
        known = ", ".join(r["name"] for r in index["runs"])
        sys.exit(f"--runs names a run that is not in {index_path} (it has: {known})")

    # Every run of the folder, scored or not, sets the start, so that scores made in turns
    # compare the same span.
    first = 0
    if not args.include_lead_in:
        first = max(lead_in_refreshes(os.path.join(args.video_dir, r["folder"]))
                    for r in index["runs"])
    frames = range(first, index["refreshes"])

    scores_path = os.path.join(args.video_dir, "jod.json")
    scores = {}
    if os.path.isfile(scores_path):
        with open(scores_path) as f:
            earlier = json.load(f)
        # Scores of another span (from another first refresh) are not kept beside these.
        if earlier.get("first_refresh", 0) == first:
            scores = earlier.get("jod", {})
        else:
            print(f"{scores_path}: dropping the scores from refresh "
                  f"{earlier.get('first_refresh', 0)} (these start at refresh {first})")
    for run in runs:
        started = time.time()
        source = PngSequence(
            os.path.join(args.video_dir, run["folder"], "displayed"),
            reference_dir,
            frames,
            index["refresh_hz"],
            viewing["name"],
        )
        with torch.no_grad():
            jod, _ = metric.predict_video_source(source)
        scores[run["name"]] = float(jod)
        print(f"{run['name']}: JOD {float(jod):.3f} ({time.time() - started:.0f} s)", flush=True)

    result = {
        "metric": f"ColorVideoVDP {version('cvvdp')}",
        "viewing": viewing,
        "video_resolution": [width, height],
        "refresh_hz": index["refresh_hz"],
        "first_refresh": first,
        "jod": scores,
    }
    temp = scores_path + ".partial"
    with open(temp, "w") as f:
        json.dump(result, f, indent=2)
        f.write("\n")
    os.replace(temp, scores_path)
    print(f"wrote {scores_path}")

    if args.summary:
        command = [find_steadyray(args.steadyray), "jod", "merge", "--scores", scores_path,
                   "--summary", args.summary]
        subprocess.run(command, check=True)


if __name__ == "__main__":
    main()
