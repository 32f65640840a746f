#!/usr/bin/env bash
# Which published contingent benchmark files kaboum reads (../shared/pddl/contingent): every
# domain/problem pair of every source, run through `kaboum contingent` with a short time limit,
# and counted per source as read (parsed, grounded and its initial worlds enumerated: solved, or
# not solved within the limit), beyond `--max-worlds`, or rejected at reading (the first message
# is listed). Prints Markdown. Usage: bench/pddl_input_coverage.sh [kaboum binary] [time limit s]
set -uo pipefail
cd "$(dirname "$0")/.."
kaboum=${1:-build/release/kaboum}
limit=${2:-10}
root=../shared/pddl/contingent
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# "source|domain file|problem file" per line. A directory's domain files start with d or domain,
# its problems with anything else; a domain pairs with the problem of the same suffix (d2.pddl
# with p2.pddl), else with every problem. PO-PRP keeps doors and colorballs problems beside one
# domain file.
pairs() {
  local dir files doms probs d p suffix match
  for dir in $(find "$root" -type d | sort); do
    case $dir in */colorballs/po-prp/problems*) continue ;; esac
    files=$(ls "$dir" | grep '\.pddl$' | grep -v hidden | grep -v ' ')
    [ -n "$files" ] || continue
    local source=${dir#"$root"/}
    source=${source%%/*}/$(echo "${dir#"$root"/}" | cut -d/ -f2)
    case $dir in
      */colorballs/po-prp)
        for p in $(find "$dir"/problems-orig -name '*.pddl' | sort); do
          echo "$source|$dir/domain.pddl|$p"
        done
        continue ;;
      */doors/po-prp)
        for p in $files; do
          case $p in
            domain*) ;;
            *-clg.pddl) echo "$source|$dir/domain-clg.pddl|$dir/$p" ;;
            *) echo "$source|$dir/domain.pddl|$dir/$p" ;;
          esac
        done
        continue ;;
    esac
    doms=$(echo "$files" | grep -iE '^(d|domain)')
    probs=$(echo "$files" | grep -viE '^(d|domain)')
    for d in $doms; do
      suffix=$(echo "$d" | sed -E 's/^(domain|d)//I')
      match=""
      for p in $probs; do
        [ "$(echo "$p" | sed -E 's/^(problem|pfile|p)//I')" = "$suffix" ] && match=$p
      done
      for p in ${match:-$probs}; do echo "$source|$dir/$d|$dir/$p"; done
    done
  done
}

pairs | while IFS='|' read -r source dfile pfile; do
  timeout $((limit + 30)) "$kaboum" contingent "$dfile" "$pfile" --quiet --time-limit "$limit" \
    > /dev/null 2> "$out/err"
  code=$?
  message=$(grep -v '^kaboum: warning' "$out/err" | head -1 | sed -E 's/^kaboum: error: [^ ]*: //')
  case $code in
    0) kind=solved ;;
    1 | 124) kind=read ;;
    *) case $message in
         *"possible worlds"*) kind=worlds ;;
         *) kind="rejected: $message" ;;
       esac ;;
  esac
  echo "$source|$kind"
done > "$out/results"

echo "| source | pairs | read | of which solved in ${limit} s | beyond --max-worlds | rejected at reading |"
echo "|---|---|---|---|---|---|"
cut -d'|' -f1 "$out/results" | sort -u | while read -r source; do
  grep "^$source|" "$out/results" | cut -d'|' -f2 > "$out/kinds"
  total=$(wc -l < "$out/kinds")
  solved=$(grep -c '^solved$' "$out/kinds")
  read=$((solved + $(grep -c '^read$' "$out/kinds")))
  worlds=$(grep -c '^worlds$' "$out/kinds")
  rejected=$(grep '^rejected' "$out/kinds" | sed 's/^rejected: //' | sort | uniq -c |
    awk '{n=$1; $1=""; printf "%s%d × %s", (NR>1 ? "; " : ""), n, substr($0, 2)}')
  echo "| $source | $total | $read | $solved | $worlds | $rejected |"
done
