#!/usr/bin/env bash
# The temporal mode's checks on a real GPU in one go (issue 17; docs/temporal.md,
# docs/subjective.md): the pass's cost at 1920x1080 (a plain frame against the same view
# after 30 frames of history, alternating), then the corridor under the real clock at the
# paper's band and at one and two refreshes, each controller without and with the history.
# Displayed FLIP is scored there; JOD needs the videos and Python (scripts/jod), which the
# device machine has not got.
#
# On the device machine, after the recipe of ../shared/gpu/README.md (the Vulkan loader
# unpacked from .gl/, the release binary in .gpu-bin/):
#     scripts/gpu/temporal.sh "$OUT/temporal"
# A dry run here on lavapipe, small and short:
#     STEADYRAY=target/release/steadyray W=160 H=90 DURATION=0.5 REPEAT=2 \
#         xvfb-run -a scripts/gpu/temporal.sh /tmp/temporal-dry
set -euo pipefail
out=${1:?usage: scripts/gpu/temporal.sh OUT_DIR}
bin=${STEADYRAY:-.gpu-bin/steadyray}
w=${W:-1920}
h=${H:-1080}
duration=${DURATION:-4}
repeat=${REPEAT:-5}
mkdir -p "$out"
size=(--backend gpu --width "$w" --height "$h")
view=(--spp 1 --depth 16 --time 0.5 --stats)
for _ in $(seq "$repeat"); do
    "$bin" render "${size[@]}" "${view[@]}" --output "$out/plain.png" | tail -n 1 >>"$out/pass-plain.jsonl"
    "$bin" render "${size[@]}" "${view[@]}" --temporal 30 --output "$out/temporal.png" |
        tail -n 1 >>"$out/pass-temporal.jsonl"
done
bench=(bench "${size[@]}" --clock real --duration "$duration" --quality --every 4)
"$bin" "${bench[@]}" --tmin 15 --tmax 20 --controllers predictive --temporal both --out "$out/paper"
"$bin" "${bench[@]}" --band refresh --controllers hysteresis,predictive --temporal both --out "$out/refresh"
"$bin" "${bench[@]}" --band refresh:2 --controllers predictive --temporal both --out "$out/refresh2"
echo "wrote $out: pass-plain.jsonl, pass-temporal.jsonl (render_ms of each), paper/, refresh/, refresh2/"
