#!/usr/bin/env bash
# The matcher's ablation on a correspondence benchmark: the seeded sample matched with the
# default options, with each stage off in turn, and by the paper's matcher alone. Prints one
# Markdown table (docs/benchmarks.md, "Ablation"): each configuration's mean error ×100 over all
# pairs, within and across subjects, its mirrored pairs, its time a pair, and its change
# against the default.
#
# Each configuration runs as JOBS one-thread shards side by side into OUT/NAME and resumes:
# pairs already there are not matched again, so a long ablation can be run in parts (stop it
# any time; run it again). They are reused whatever build made them: give a new build a new OUT.
#
# A stage whose candidate a match did not keep left that match as if it had not run (the rules
# keep a candidate or leave everything as it was; tests/matching/stages_test.cpp checks it). So
# where the default run's `details` say a stage kept nothing, the configuration without it
# takes the default's pair as it is, and only the pairs the stage changed are matched again;
# the table counts them ("matched"), and its time a pair is then the default's on the others.
# A stage that only replaces a candidate's result by one that disagrees less (the signature
# fallback) is reusable too: left out from a candidate that was not kept, it leaves that
# candidate disagreeing as much or more, so the same one is kept.
#
# Usage: bench/ablation.sh [-b GENFLOW] [-d SHAPES] [-o OUT] [-n PAIRS] [-s SEED] [-j JOBS]
#                          [-k SUBJECT_SIZE] [CONFIGURATION...]
# Defaults: build/release/genflow, $GENFLOW_DATA/benchmarks/faust_r_train, ablation/, 100 pairs,
# seed 1, 2 jobs, subjects of 10, every configuration (bench/ablation.sh -l lists them).
set -euo pipefail

# name | flags of `genflow benchmark` | what the configuration leaves out | where the default's
# pair is reused (`details` fields whose value says the stage kept nothing)
configurations=(
  "default||nothing|"
  "no-start-selection|--candidates 1|the rigid starts' selection flows: the best rigid fit goes on"
  "no-guided-rounds|--signature-guidance 0|every guided round (signatures, eigenfunctions, stretching) and the second coarsest level's refinement and checks"
  "no-eigenfunctions|--eigenfunction-guidance 0|the eigenfunction-guided last round and refinement (the last round guided by the signatures)"
  "no-stretching|--stretch-weight 0|the stretching energy of the last round (and so its stiffness candidates)"
  "no-stiffness-candidates|--stiffness-candidates 1|the stiffer last rounds"
  "no-signatures-reading|--no-signatures-reading|the match made again with the eigenfunctions off, kept if its map commutes better|signatures_reading=false"
  "no-signature-fallback|--no-signature-fallback|a doubtful last round's rerun guided by the signatures|signature_fallback=false"
  "no-second-opinion|--second-opinion-above inf|the intrinsic start (and with it the alternative starts and the coarsest limb exchange)"
  "no-alternative-starts|--alternative-starts 0|the further intrinsic starts of a doubtful result|alternative_start=0"
  "no-limb-swaps|--no-limb-swaps|the limb exchanges at both levels|swapped_limbs=0"
  "no-refinement|--refinement-guidances 0|the second coarsest level's eigenfunction-guided flows|refinement_guidance=0.0"
  "no-turn-back|--no-turn-back|turning back parts a fine map places turned over|turned_parts=0"
  "no-map-fits|--map-fits 0|the fits to the fine functional map|map_fits=0"
  "no-counterparts|--no-counterparts|the counterparts chosen by the eigenfunctions: each vertex's closest point on the target|"
  "no-reruns|--stiffness-candidates 1 --second-opinion-above inf --alternative-starts 0 --no-signature-fallback|every stage that runs the guided rounds again: stiffer rounds, the fallback, the second opinion and alternative starts (and so the limb exchanges)"
  "paper|--preset paper|everything: eq. 14 over the levels from the inputs' frames"
)

binary=build/release/genflow
shapes=${GENFLOW_DATA:-../shared/data}/benchmarks/faust_r_train
out=ablation
pairs=100
seed=1
jobs=2
subject_size=10
list=false
while getopts "b:d:o:n:s:j:k:l" option; do
  case $option in
    b) binary=$OPTARG ;;
    d) shapes=$OPTARG ;;
    o) out=$OPTARG ;;
    n) pairs=$OPTARG ;;
    s) seed=$OPTARG ;;
    j) jobs=$OPTARG ;;
    k) subject_size=$OPTARG ;;
    l) list=true ;;
    *)
      echo "usage: bench/ablation.sh [-b GENFLOW] [-d SHAPES] [-o OUT] [-n PAIRS] [-s SEED]" \
        "[-j JOBS] [-k SUBJECT_SIZE] [-l] [CONFIGURATION...]" >&2
      exit 2
      ;;
  esac
done
shift $((OPTIND - 1))

if $list; then
  for entry in "${configurations[@]}"; do
    IFS='|' read -r name flags leaves_out _ <<<"$entry"
    printf '%-24s %-30s %s\n' "$name" "${flags:-(none)}" "$leaves_out"
  done
  exit 0
fi
if [[ ! -x $binary ]]; then
  echo "ablation.sh: $binary is not an executable (build it, or pass -b)" >&2
  exit 2
fi
if [[ ! -d $shapes ]]; then
  echo "ablation.sh: $shapes is not a directory (set GENFLOW_DATA, or pass -d)" >&2
  exit 2
fi
if ! [[ $jobs =~ ^[1-9][0-9]*$ ]]; then
  echo "ablation.sh: -j needs a positive integer, got '$jobs'" >&2
  exit 2
fi

wanted=("$@")
chosen=()
for entry in "${configurations[@]}"; do
  IFS='|' read -r name _ <<<"$entry"
  if [[ ${#wanted[@]} -eq 0 || " ${wanted[*]} " == *" $name "* ]]; then
    chosen+=("$entry")
  fi
done
for name in "${wanted[@]}"; do
  if ! printf '%s\n' "${configurations[@]}" | cut -d'|' -f1 | grep -qx -- "$name"; then
    echo "ablation.sh: no configuration '$name' (bench/ablation.sh -l lists them)" >&2
    exit 2
  fi
done

common=(--pairs "$pairs" --seed "$seed" --subject-size "$subject_size")

# Whether the default's pair FILE (its JSON) says the stage kept nothing: every field=value of
# UNCHANGED_WHERE is in its details.
kept_nothing() {
  local file=$1 unchanged_where=$2 condition
  for condition in ${unchanged_where//,/ }; do
    grep -q "\"${condition%%=*}\":${condition#*=}[,}]" "$file" || return 1
  done
}

# The default's pairs in which the stage kept nothing, taken as they are into DIR; their names
# are listed in DIR/reused.txt.
reuse_unchanged_pairs() {
  local dir=$1 unchanged_where=$2 file pair
  [[ -n $unchanged_where && -d $out/default/pairs ]] || return 0
  mkdir -p "$dir/pairs"
  for file in "$out"/default/pairs/*.json; do
    [[ -e $file ]] || continue
    pair=$(basename "$file" .json)
    if [[ ! -e $dir/pairs/$pair.json ]] && kept_nothing "$file" "$unchanged_where"; then
      cp "$out/default/pairs/$pair.map.txt" "$dir/pairs/"
      cp "$file" "$dir/pairs/"
      echo "$pair" >>"$dir/reused.txt"
    fi
  done
}

# One configuration: the default's pairs it would not change, then its shards side by side (one
# thread each: the machine's cores go to the shards), then the summary of all its pairs.
run_configuration() {
  local name=$1 flags=$2 unchanged_where=$3 dir=$out/$1
  mkdir -p "$dir"
  reuse_unchanged_pairs "$dir" "$unchanged_where"
  local shard
  local -a pids=()
  for ((shard = 0; shard < jobs; ++shard)); do
    # shellcheck disable=SC2086 # the flags are words
    OMP_NUM_THREADS=1 "$binary" benchmark "$shapes" "${common[@]}" $flags --output-dir "$dir" \
      --resume --shard "$shard/$jobs" >"$dir/shard$shard.md" 2>"$dir/shard$shard.err" &
    pids+=($!)
  done
  local failed=0
  for pid in "${pids[@]}"; do
    wait "$pid" || failed=1
  done
  # shellcheck disable=SC2086
  "$binary" benchmark "$shapes" "${common[@]}" $flags --output-dir "$dir" --resume \
    >"$dir/summary.md" 2>"$dir/summary.err" || failed=1
  if [[ $failed -ne 0 ]]; then
    echo "ablation.sh: $name: a run failed (see $dir/*.err)" >&2
  fi
}

# The summary row of `genflow benchmark` for a set of pairs ("all", "within subjects", ...):
# its error ×100, mirrored pairs and mean time.
summary_field() {
  local file=$1 set=$2 column=$3
  awk -F'|' -v set="$set" -v column="$column" '
    { gsub(/^ +| +$/, "", $2) }
    $2 == set { value = $column; gsub(/^ +| +$/, "", value); print value; exit }' "$file"
}

for entry in "${chosen[@]}"; do
  IFS='|' read -r name flags _ unchanged_where <<<"$entry"
  echo "ablation.sh: $name ($pairs pairs, $jobs shards)" >&2
  run_configuration "$name" "$flags" "$unchanged_where"
done

echo "| configuration | leaves out | error ×100 | within | across | mirrored | matched | time a pair | change |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|"
default_error=
if [[ -f $out/default/summary.md ]]; then
  default_error=$(summary_field "$out/default/summary.md" all 4)
fi
for entry in "${chosen[@]}"; do
  IFS='|' read -r name flags leaves_out _ <<<"$entry"
  file=$out/$name/summary.md
  reused=0
  if [[ -f $out/$name/reused.txt ]]; then
    reused=$(wc -l <"$out/$name/reused.txt")
  fi
  error=$(summary_field "$file" all 4)
  within=$(summary_field "$file" "within subjects" 4)
  across=$(summary_field "$file" "across subjects" 4)
  mirrored=$(summary_field "$file" all 8)
  time=$(summary_field "$file" all 10)
  change=
  if [[ -n $default_error && -n $error && $name != default ]]; then
    change=$(awk -v a="$default_error" -v b="$error" 'BEGIN { printf "%+.2f", b - a }')
  fi
  echo "| \`$name\` | $leaves_out | $error | $within | $across | $mirrored | $((pairs - reused)) | $time | $change |"
done
