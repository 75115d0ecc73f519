#!/usr/bin/env bash
# Runs `rts test` on a Slurm cluster: one array task per shard, then a merge job that waits for
# all of them (afterany: it also runs when a shard failed or was cancelled, and names the cases
# that are missing). Docs: docs/cluster.md.
#
#   tools/cluster/slurm_array.sh --shards N --out DIR [--rts PATH] [--cpus C] [--wait]
#       [--sbatch-arg ARG]... -- TEST_ARGS...
#
# TEST_ARGS are those of `rts test` (scenario folders or files, --seeds ...); the script adds
# --shard K/N, --report-dir DIR/shard-K and --junit DIR/shard-K/junit.xml to each task and
# --jobs C when --cpus is given. The merge writes DIR/merged/ (summary.json, cases/, junit.xml)
# and its console output to DIR/logs/merge.out. Paths must be the same on every node (a shared
# filesystem). With --wait the script waits for the merge and exits with its status (0 every
# case passed; 1 a case failed, is missing or duplicated); without it, it prints the job ids.
set -euo pipefail

usage() {
  sed -n '5,7p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
}

shards=""
out=""
rts="$(cd "$(dirname "$0")/../.." && pwd)/build/tools/rts"
cpus=""
wait=0
sbatch_args=()
while (($#)); do
  case "$1" in
    --shards) shards="${2:-}"; shift 2 ;;
    --out) out="${2:-}"; shift 2 ;;
    --rts) rts="${2:-}"; shift 2 ;;
    --cpus) cpus="${2:-}"; shift 2 ;;
    --wait) wait=1; shift ;;
    --sbatch-arg) sbatch_args+=("${2:-}"); shift 2 ;;
    --) shift; break ;;
    *) echo "slurm_array: unknown option '$1'" >&2; usage ;;
  esac
done
test_args=("$@")
[[ "$shards" =~ ^[1-9][0-9]*$ ]] || { echo "slurm_array: --shards must be a whole number >= 1" >&2; usage; }
[[ -n "$out" ]] || { echo "slurm_array: --out DIR is required" >&2; usage; }
[[ -z "$cpus" || "$cpus" =~ ^[1-9][0-9]*$ ]] || { echo "slurm_array: --cpus must be a whole number >= 1" >&2; usage; }
((${#test_args[@]})) || { echo "slurm_array: give rts test's arguments after --" >&2; usage; }
[[ -x "$rts" ]] || { echo "slurm_array: no rts program at '$rts' (build it, or pass --rts)" >&2; exit 2; }
command -v sbatch >/dev/null || { echo "slurm_array: sbatch not found (tools/setup.sh --cluster)" >&2; exit 2; }

mkdir -p "$out/logs"
out="$(cd "$out" && pwd)"
rts="$(cd "$(dirname "$rts")" && pwd)/$(basename "$rts")"

jobs_args=()
cpu_args=()
if [[ -n "$cpus" ]]; then
  jobs_args=(--jobs "$cpus")
  cpu_args=(--cpus-per-task="$cpus")
fi

# The scripts are written out with every argument quoted, so paths with spaces survive.
task_script="$out/shard_task.sh"
{
  echo '#!/usr/bin/env bash'
  echo 'k="$SLURM_ARRAY_TASK_ID"'
  printf 'exec %q test' "$rts"
  printf ' %q' "${test_args[@]}" "${jobs_args[@]}"
  printf ' --shard "$k/%d" --report-dir %q/shard-"$k" --junit %q/shard-"$k"/junit.xml\n' \
    "$shards" "$out" "$out"
} >"$task_script"

merge_script="$out/merge_task.sh"
{
  echo '#!/usr/bin/env bash'
  printf 'exec %q test merge' "$rts"
  for ((k = 0; k < shards; k++)); do printf ' %q' "$out/shard-$k"; done
  printf ' --report-dir %q --junit %q\n' "$out/merged" "$out/merged/junit.xml"
} >"$merge_script"
chmod +x "$task_script" "$merge_script"

array_id=$(sbatch --parsable --job-name=rts-test --array="0-$((shards - 1))" \
  --output="$out/logs/shard-%a.out" "${cpu_args[@]}" "${sbatch_args[@]}" "$task_script")
array_id="${array_id%%;*}"  # "id;cluster" on federated clusters
echo "slurm_array: array job $array_id ($shards shards)"

merge_args=(--parsable --job-name=rts-test-merge --dependency="afterany:$array_id"
  --output="$out/logs/merge.out" "${sbatch_args[@]}")
if ((wait)); then
  status=0
  sbatch --wait "${merge_args[@]}" "$merge_script" >/dev/null || status=$?
  echo "slurm_array: merged into $out/merged (exit $status)"
  cat "$out/logs/merge.out"
  exit "$status"
fi
merge_id=$(sbatch "${merge_args[@]}" "$merge_script")
echo "slurm_array: merge job ${merge_id%%;*} writes $out/merged"
