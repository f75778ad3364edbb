#!/usr/bin/env bash
# Opt-in (not in CI): closest-hit throughput of `bvh::Bvh::closest_hit`
# against Intel Embree 4 (`rtcIntersect1` through PyPI embreex) on the
# renderer's primary rays — one per pixel of the default scene's 512 x 512
# camera (bunny over a floor, 3676 triangles) — same rays, same machine,
# same run:
#
#     bash benches/compare_embree_primary.sh [outdir]
#
# Needs the venv of benches/compare_embree.sh (override its path with
# VENV=...). Steps: `examples/primary_corpus.rs` writes the corpus
# (`primary.rays`, format in that file) to outdir (default
# target/ray_corpus), times ours on 2 threads (rayon over image rows) and
# writes our per-ray hits; then `benches/embree_primary.py` times Embree on
# the same rays (2 worker processes; with and without its per-ray output
# arrays) and compares hit/miss, triangle and t per ray. Both report the
# median of 7 repetitions after a warm-up, wall and CPU time; on a shared
# machine rays per CPU-second is the steadier figure. Environment: REPS
# (Embree repetitions, default 7), plus the usual CARGO_TARGET_DIR.
set -euo pipefail

source "$(dirname "$0")/embree_env.sh"
OUTDIR=${1:-target/ray_corpus}
run_both primary_corpus reference,scene-file benches/embree_primary.py "$OUTDIR"
awk "$AWK_FIELD"'
    FNR == 1 { file++ }
    /^RESULT/ {
        if (file == 1) {
            ours = field($0, "rays_per_s"); ourcpu = field($0, "rays_per_cpu_s")
            ourhits = field($0, "hits")
        } else {
            row++
            mode[row] = field($0, "mode"); emb[row] = field($0, "rays_per_s")
            embcpu[row] = field($0, "rays_per_cpu_s"); embhits[row] = field($0, "hits")
            dis[row] = field($0, "hit_miss_disagree"); tri[row] = field($0, "other_triangle")
            t6[row] = field($0, "t_within_1e-6")
        }
    }
    END {
        printf "| Embree mode | ours Mrays/s | Embree Mrays/s | ours ÷ Embree | ours Mrays/CPU-s | Embree Mrays/CPU-s | ours ÷ Embree (CPU) | hits (ours) | hits (Embree) | hit/miss differs | other triangle | t within 1e-6 |\n"
        printf "|---|---|---|---|---|---|---|---|---|---|---|---|\n"
        for (i = 1; i <= row; i++) {
            o = ours + 0; oc = ourcpu + 0; e = emb[i] + 0; ec = embcpu[i] + 0
            printf "| %s | %.3f | %.3f | %s | %.3f | %.3f | %s | %s | %s | %s | %s | %s |\n", mode[i],
                o / 1e6, e / 1e6, (e > 0 ? sprintf("%.2f", o / e) : "-"),
                oc / 1e6, ec / 1e6, (ec > 0 ? sprintf("%.2f", oc / ec) : "-"),
                ourhits, embhits[i], (dis[i] == "" ? "-" : dis[i]), (tri[i] == "" ? "-" : tri[i]),
                (t6[i] == "" ? "-" : t6[i])
        }
    }
' "$LOG/ours.txt" "$LOG/embree.txt"
