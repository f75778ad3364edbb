#!/usr/bin/env bash
# Opt-in (not in CI): the Monte Carlo reference's own rays against Intel
# Embree 4 (`rtcOccluded1` through PyPI embreex), same rays, same machine,
# same run:
#
#     bash benches/compare_embree_mc.sh [outdir]
#
# Needs the venv of benches/compare_embree.sh (VENV=..., default
# /work/venv-embree, with embreex and numpy).
#
# Steps: `examples/mc_corpus.rs` writes the corpus — the default scene
# (rounded to f32) and the rays `monte_carlo::visibility` casts from its
# floor receivers in the exact penumbra (RECEIVERS, default 256, at
# SAMPLES, default 4096, each) — to outdir (default target/mc_corpus), times
# our occlusion rays on them and the Monte Carlo reference as a whole on 2
# threads, and writes our per-ray answers; then `benches/embree_compare.py`
# times Embree on the same rays (2 worker processes; default and robust
# scene flags) and compares the per-ray answers. Medians of 7 repetitions
# after a warm-up; rays per CPU-second is the steadier figure. WITH_FLOOR=1
# keeps the floor the receivers lie on (Embree's robust mode then counts
# every ray occluded at t = 0; its default mode agrees with ours).
set -euo pipefail

source "$(dirname "$0")/embree_env.sh"
OUTDIR=${1:-target/mc_corpus}
RECEIVERS=${RECEIVERS:-256}
SAMPLES=${SAMPLES:-4096}
EMBREE_ARGS="--scenes mc-default"
run_both mc_corpus reference,scene-file benches/embree_compare.py "$OUTDIR" "$RECEIVERS" "$SAMPLES" ${WITH_FLOOR:+with-floor}
awk "$AWK_FIELD"'
    FNR == 1 { file++ }
    /^RESULT/ {
        scene = field($0, "scene")
        if (file == 1) {
            name[scene] = scene; cpu[scene] = field($0, "rays_per_cpu_s"); wall[scene] = field($0, "rays_per_s")
        } else {
            row++; mode[row] = field($0, "mode"); ecpu[row] = field($0, "rays_per_cpu_s")
            ewall[row] = field($0, "rays_per_s"); dis[row] = field($0, "disagree")
        }
    }
    END {
        printf "| ours | Embree scene flags | ours Mrays/CPU-s | Embree Mrays/CPU-s | ours ÷ Embree (CPU) | ours Mrays/s | Embree Mrays/s | disagreeing rays |\n"
        printf "|---|---|---|---|---|---|---|---|\n"
        split("mc-default mc-default-workload", ours, " ")
        for (k = 1; k <= 2; k++) {
            s = ours[k]
            for (i = 1; i <= row; i++) {
                printf "| %s | %s | %.3f | %.3f | %.2f | %.3f | %.3f | %s |\n", s, mode[i],
                    cpu[s] / 1e6, ecpu[i] / 1e6, (ecpu[i] > 0 ? cpu[s] / ecpu[i] : 0),
                    wall[s] / 1e6, ewall[i] / 1e6, (k == 1 ? dis[i] : "-")
            }
        }
    }
' "$LOG/ours.txt" "$LOG/embree.txt"
