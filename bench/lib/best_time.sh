# Sourced by the benchmark scripts: best RUNS (default 1) wall time of a command.
#   best COMMAND ARGS...   prints the fastest of $runs runs, in seconds (stdout discarded)
runs="${RUNS:-1}"

best() {
  local best_s=""
  for _ in $(seq "$runs"); do
    local t0 t1
    t0=$(date +%s.%N)
    "$@" >/dev/null
    t1=$(date +%s.%N)
    best_s=$(echo "$t0 $t1 ${best_s:-1e9}" | awk '{d = $2 - $1; print (d < $3 ? d : $3)}')
  done
  echo "$best_s"
}
