# Shell functions for the scripts that turn a benchmark run into a committed, dated result
# file (chapters/*/..._results.md). Source it from the repository root:
#   . bench/committed_run.sh
#   require_csv "$csv" "name.sh"            # exit 2 with a message when the run is missing
#   measured_line "$csv" "what was run"     # the date, machine, compiler and method
set -eu

# Stops the calling script (exit 2) when the run's CSV is missing or empty.
require_csv() {
    [ -s "$1" ] || { echo "$2: no $1: run the benchmark first (see its usage)" >&2; exit 2; }
}

# One paragraph: when and where the run was measured, and how (pinned to one core, five
# repetitions in random order, the median), naming what ran ($2).
measured_line() {
    cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
    echo "Measured $(date -u -r "$1" +%Y-%m-%d) on $(uname -m), $(nproc) cores ($cpu)," \
         "$(c++ --version | head -n 1), Release build, pinned to one core, each benchmark" \
         "repeated five times in random order and the median taken ($2)."
}
