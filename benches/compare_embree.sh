#!/usr/bin/env bash
# Opt-in (not in CI): occlusion-ray throughput of our exact
# `bvh::Bvh::segment_unoccluded` (the 8-wide occlusion tree, packs of
# triangles tested in f32 under a proven bound, the exact f64 test for
# every uncertain one) against Intel Embree 4
# (`rtcOccluded1` through PyPI embreex), same rays, same machine, same run:
#
#     bash benches/compare_embree.sh [outdir]
#
# Needs a venv with embreex and numpy (override its path with VENV=...):
#
#     python3 -m venv /work/venv-embree
#     /work/venv-embree/bin/pip install embreex numpy
#
# Steps: `examples/ray_corpus.rs` writes the two corpora (100k-triangle soup,
# 100,820-triangle closed geodesic sphere; 1M floor-to-area-light rays each;
# format in that file) to outdir (default target/ray_corpus), times ours on
# 2 threads and writes our per-ray answers; then `benches/embree_compare.py`
# times Embree on the same rays (2 worker processes, as embreex does not
# release the GIL for long; default and robust scene flags) and compares the
# per-ray answers. Both report the median of 7 repetitions after a warm-up;
# both also measure CPU time, since rays per CPU-second is the steadier
# figure when other work shares the cores. Environment: RAYS (rays per scene,
# default 1000000), SEED (default 2026), REPS (Embree repetitions, default
# 7), plus the usual CARGO_TARGET_DIR.
set -euo pipefail

source "$(dirname "$0")/embree_env.sh"
OUTDIR=${1:-target/ray_corpus}
RAYS=${RAYS:-1000000}
SEED=${SEED:-2026}
run_both ray_corpus reference,arbitrary benches/embree_compare.py "$OUTDIR" "$RAYS" "$SEED"
awk "$AWK_FIELD"'
    FNR == 1 { file++ }
    /^RESULT/ {
        scene = field($0, "scene")
        if (file == 1) {
            ours[scene] = field($0, "rays_per_s"); ourhits[scene] = field($0, "hits")
            ourcpu[scene] = field($0, "rays_per_cpu_s")
        } else {
            row++
            rs[row] = scene; mode[row] = field($0, "mode")
            emb[row] = field($0, "rays_per_s"); embhits[row] = field($0, "hits")
            dis[row] = field($0, "disagree"); embcpu[row] = field($0, "rays_per_cpu_s")
        }
    }
    END {
        printf "| scene | Embree scene flags | ours Mrays/s | Embree Mrays/s | Embree ÷ ours | ours Mrays/CPU-s | Embree Mrays/CPU-s | Embree ÷ ours (CPU) | occluded (ours) | occluded (Embree) | disagreeing rays |\n"
        printf "|---|---|---|---|---|---|---|---|---|---|---|\n"
        for (i = 1; i <= row; i++) {
            s = rs[i]
            o = ours[s] + 0; oc = ourcpu[s] + 0; ec = embcpu[i] + 0
            printf "| %s | %s | %.3f | %.3f | %s | %.3f | %.3f | %s | %s | %s | %s |\n", s, mode[i],
                o / 1e6, emb[i] / 1e6, (o > 0 ? sprintf("%.2f", emb[i] / o) : "-"),
                oc / 1e6, ec / 1e6, (oc > 0 ? sprintf("%.2f", ec / oc) : "-"),
                ourhits[s], embhits[i], (dis[i] == "" ? "-" : dis[i])
        }
    }
' "$LOG/ours.txt" "$LOG/embree.txt"
