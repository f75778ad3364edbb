# Sourced by benches/compare_embree.sh and benches/compare_embree_primary.sh
# (not run on its own): the repository root as working directory, the
# Embree venv checked (VENV, default /work/venv-embree), REPS (Embree
# repetitions, default 7), a log directory $LOG removed on exit, and the
# machine line printed.
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
