#!/usr/bin/env bash
# The temporal mode's checks on a real GPU in one go (issue 17; docs/temporal.md,
# docs/subjective.md), in the order of what matters most, each stage skipped when too little
# of the time budget is left for it:
#   1. pass: the pass's cost at 1920x1080 (a plain frame against the same view after 30
#      frames of history, alternating; render_ms by GPU timestamps);
#   2. still: a still corridor view, one frame at S against the history of 31 frames (1 s at
#      the paper's band) at S, both against a reference at S = STILL_REF_SPP (default 4096:
#      a history of 31 frames at S = 16 holds 496 samples; steadyray compare);
#   3. paper, refresh, paper-reversed, refresh2: the corridor under the real clock at the
#      paper's band, at one refresh, at the paper's band again with the history's run first
#      (the GPU's clocks follow its load), and at two refreshes, each controller without and
#      with the history and its warped refreshes (`--temporal both --warp`, the issue's
#      comparison as the CPU's benches make it), displayed FLIP,
#      the screen videos (references at S = REF_SPP), and their JOD (scripts/jod/jod.py)
#      when python3 has torch and pycvvdp (carry the wheels cvvdp, ffmpeg-python and future,
#      installed with --target and PYTHONPATH: see the device recipe);
#   4. paper-nowarp: the paper's band with the history and no warps, to set beside the
#      device sessions before the warps (docs/subjective.md).
# Small results (summaries, tables, frames.csv, jod.json, the still view's figures) are packed
# into OUT/results.tar.gz after every stage, so a run cut short still returns what it did.
#
# On the device machine, set up as docs/gpu.md says (the Vulkan loader's Debian packages
# unpacked from .gl/, the release binary in .gpu-bin/), with ColorVideoVDP's wheels in .whl/
# (here: python -m pip download --no-deps --only-binary=:all: --python-version 3.12
#  --implementation cp --platform any -d .whl cvvdp==0.5.7 ffmpeg-python==0.2.0 future;
# the device's python3 has torch, numpy and the rest):
#     for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
#     python3 -m pip install -q --no-index --no-deps --target /tmp/site .whl/*.whl
#     PYTHONPATH=/tmp/site WGPU_BACKEND=vulkan RUST_LOG=warn HF_HUB_OFFLINE=1 \
#         scripts/gpu/temporal.sh "$OUT"
# (pass, still, paper, refresh and refresh2 took about 460 s on an H200; BUDGET_S, default
# 520, skips the stages that would not fit; STAGES lists the stages to run, in order;
# REFRESH_CONTROLLERS, default hysteresis,predictive, the controllers of `refresh`).
# A dry run here on lavapipe, small and short:
#     STEADYRAY=target/release/steadyray W=160 H=90 DURATION=0.5 REPEAT=2 REF_SPP=16 \
#         xvfb-run -a scripts/gpu/temporal.sh /tmp/temporal-dry
set -euo pipefail
out=${1:?usage: scripts/gpu/temporal.sh OUT_DIR}
bin=${STEADYRAY:-.gpu-bin/steadyray}
w=${W:-1920}
h=${H:-1080}
duration=${DURATION:-4}
repeat=${REPEAT:-3}
budget=${BUDGET_S:-520}
ref_spp=${REF_SPP:-256}
still_ref_spp=${STILL_REF_SPP:-4096}
still_spp=${STILL_SPP:-1 4 16}
work=${WORK:-/tmp/steadyray-temporal}
mkdir -p "$out" "$work"
log="$work/log.txt"
exec > >(tee -a "$log") 2>&1

# Whether at least $1 seconds of the budget are left; says so when not.
left() {
    if (( budget - SECONDS < $1 )); then
        echo "skipped: $2 (needs about $1 s, $(( budget - SECONDS )) s left)"
        return 1
    fi
}
pack() {
    (cd "$work" && find . \( -name '*.json' -o -name '*.jsonl' -o -name '*.md' -o -name '*.csv' \
        -o -name '*.txt' -o -name frametime.png \) -not -path '*/displayed/*' \
        -not -path '*/reference/*' -not -name timings.csv -print0 |
        tar --null -czf "$out/results.tar.gz.partial" -T -) &&
        mv "$out/results.tar.gz.partial" "$out/results.tar.gz"
}
jod() {
    if python3 -c 'import pycvvdp, torch' 2>/dev/null; then
        python3 scripts/jod/jod.py "$1" --summary "$2/summary.json" --steadyray "$bin" || true
    else
        echo "no JOD: python3 lacks pycvvdp or torch"
    fi
}

size=(--backend gpu --width "$w" --height "$h")
stage_pass() {
    local view=(--spp 1 --depth 16 --time 0.5 --stats)
    for _ in $(seq "$repeat"); do
        "$bin" render "${size[@]}" "${view[@]}" --output "$work/plain.png" |
            tail -n 1 >>"$work/pass-plain.jsonl"
        "$bin" render "${size[@]}" "${view[@]}" --temporal 30 --output "$work/temporal.png" |
            tail -n 1 >>"$work/pass-temporal.jsonl"
    done
}
stage_still() {
    local still=(render "${size[@]}" --yaw 20 --depth 16)
    "$bin" "${still[@]}" --spp "$still_ref_spp" --reference --output "$work/still-reference.png" >/dev/null
    for s in $still_spp; do
        "$bin" "${still[@]}" --spp "$s" --output "$work/still-one-$s.png" >/dev/null
        "$bin" "${still[@]}" --spp "$s" --temporal 31 --output "$work/still-history-$s.png" >/dev/null
        for kind in one history; do
            printf '{"spp":%s,"kind":"%s","compare":%s}\n' "$s" "$kind" \
                "$("$bin" compare "$work/still-reference.png" "$work/still-$kind-$s.png")" \
                >>"$work/still.jsonl"
        done
    done
}

bench=(bench "${size[@]}" --clock real --duration "$duration" --quality --every 4
    --reference-spp "$ref_spp")
references=""
# Runs one bench into $work/$1 with its video in $work/$1-video (the references of the first
# bench linked in: same scene, size, rate and length), then its JOD.
run_bench() {
    local name=$1
    shift
    local video="$work/$name-video"
    mkdir -p "$video"
    if [[ -n "$references" && ! -e "$video/reference" ]]; then
        cp -al "$references" "$video/reference"
    fi
    "$bin" "${bench[@]}" "$@" --video "$video" --out "$work/$name"
    if [[ -z "$references" ]]; then
        references="$video/reference"
    fi
    pack
    jod "$video" "$work/$name"
    rm -rf "$video"/*/displayed "$video"/*.y4m "$video"/*/*.y4m
    pack
}
paper=(--tmin 15 --tmax 20 --controllers predictive)
warp=(--temporal both --warp)
# The GPU's clocks follow its load, so the run that comes second may start on other clocks:
# `paper-reversed` runs the paper's band again with the history first.
for stage in ${STAGES:-pass still paper refresh paper-reversed refresh2 paper-nowarp}; do
    case $stage in
        pass) left 30 pass && stage_pass && pack ;;
        still) left 40 still && stage_still && pack ;;
        paper) left 150 paper && run_bench paper "${paper[@]}" "${warp[@]}" ;;
        refresh) left 200 refresh &&
            run_bench refresh --band refresh --controllers "${REFRESH_CONTROLLERS:-hysteresis,predictive}" \
                "${warp[@]}" ;;
        paper-reversed) left 160 paper-reversed &&
            run_bench paper-history-first "${paper[@]}" --temporal on --warp &&
            run_bench paper-plain-second "${paper[@]}" --temporal off ;;
        refresh2) left 110 refresh2 &&
            run_bench refresh2 --band refresh:2 --controllers predictive "${warp[@]}" ;;
        paper-nowarp) left 90 paper-nowarp &&
            run_bench paper-nowarp "${paper[@]}" --temporal on ;;
        *) echo "unknown stage $stage (pass, still, paper, refresh, paper-reversed, refresh2, paper-nowarp)"
            exit 2 ;;
    esac
done
pack
echo "wrote $out/results.tar.gz after $SECONDS s"
