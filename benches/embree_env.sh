# Sourced by benches/compare_embree.sh and benches/compare_embree_primary.sh
# (not run on its own): the repository root as working directory, the
# Embree venv checked (VENV, default /work/venv-embree), REPS (Embree
# repetitions, default 7), a log directory $LOG removed on exit, and the
# machine line printed; then `run_both` and `$AWK_FIELD` for the two
# scripts' common steps.
cd "$(dirname "${BASH_SOURCE[0]}")/.."
VENV=${VENV:-/work/venv-embree}
REPS=${REPS:-7}
LOG=$(mktemp -d)
trap 'rm -rf "$LOG"' EXIT

if [[ ! -x "$VENV/bin/python" ]] || ! "$VENV/bin/python" -c 'import embreex, numpy' 2>/dev/null; then
    echo "no embreex in $VENV: python3 -m venv $VENV && $VENV/bin/pip install embreex numpy" >&2
    exit 1
fi

echo "== machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg)"

# run_both EXAMPLE FEATURES PYSCRIPT OUTDIR [EXAMPLE ARGS...]: builds and runs
# our example (output in $LOG/ours.txt), then the Embree half on the same
# corpus (with the words of EMBREE_ARGS after its own) (2 worker processes, $REPS repetitions; output in
# $LOG/embree.txt), then prints the table's heading lines.
run_both() {
    local example=$1 features=$2 script=$3 outdir=$4
    shift 4
    echo "== ours: cargo run --release --example $example --features $features -- $outdir $*"
    cargo build --quiet --release --example "$example" --features "$features"
    cargo run --quiet --release --example "$example" --features "$features" -- "$outdir" "$@" |
        tee "$LOG/ours.txt"
    # shellcheck disable=SC2086  # EMBREE_ARGS: further words for the script
    echo "== Embree: $VENV/bin/python $script $outdir --reps $REPS --threads 2 ${EMBREE_ARGS:-}"
    "$VENV/bin/python" "$script" "$outdir" --reps "$REPS" --threads 2 ${EMBREE_ARGS:-} |
        tee "$LOG/embree.txt"
    echo "== load after: $(cut -d' ' -f1-3 /proc/loadavg)"
    echo
    echo "Embree $(awk '/^EMBREE_VERSION/ {print $2}' "$LOG/embree.txt"); 2 threads (ours) / 2 processes (Embree);"
    echo "Mrays/s from the median wall time, Mrays/CPU-s from the median CPU time of the repetitions"
    echo
}

# An awk function: the value of `key=value` in a RESULT line, "" if absent.
# shellcheck disable=SC2034  # used by the scripts that source this file
AWK_FIELD='
    function field(line, key,    n, i, kv, parts) {
        n = split(line, parts, " ")
        for (i = 1; i <= n; i++) {
            split(parts[i], kv, "=")
            if (kv[1] == key) return kv[2]
        }
        return ""
    }'
