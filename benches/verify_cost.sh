#!/usr/bin/env bash
# What `verify` and `compensate` cost beside `check` of the same program: CPU time
# (user + sys) and peak resident memory of each, from `/usr/bin/time -v`, on the generated
# benchmark program, on the finished-part measure (their default) and pass by pass
# (`--passes`), the five commands run in turn in each round (so a busy moment of the machine
# spreads over all), medians of the rounds, and the load average beside them.
#
#   benches/verify_cost.sh [MB] [ROUNDS]      (default: 50 MB, 3 rounds)
#
# Runs from the repository's root; builds the release binary first, generates the program
# into target/bench-data/big-MB.nc on first use (as `cargo bench --bench compensate` does)
# and compensates for benches/compensate-model.toml. The README's performance table quotes
# its output.
set -euo pipefail

mb="${1:-50}"
rounds="${2:-3}"
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"

if [ ! -x /usr/bin/time ]; then
    echo "verify_cost: /usr/bin/time is missing (Debian package 'time'); nothing measured" >&2
    exit 2
fi
cargo build --release --quiet
binary="$root/target/release/turnpass"
model="$root/benches/compensate-model.toml"
program="$root/target/bench-data/big-$mb.nc"
if [ ! -f "$program" ]; then
    mkdir -p "$root/target/bench-data"
    python3 "$root/../shared/bench/gen_lathe.py" "$program" "$mb"
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
written="$work/compensated.nc"

# One run of the command named $1 (the rest are its arguments): appends
# "NAME CPU_SECONDS PEAK_KB" to $work/runs.
run() {
    local name="$1"
    shift
    /usr/bin/time -v "$binary" "$@" >"$work/out" 2>"$work/time" || {
        echo "verify_cost: turnpass $* failed:" >&2
        cat "$work/out" "$work/time" >&2
        exit 1
    }
    awk -v name="$name" '
        /User time \(seconds\)/ { user = $NF }
        /System time \(seconds\)/ { sys = $NF }
        /Maximum resident set size/ { peak = $NF }
        END { printf "%s %.2f %d\n", name, user + sys, peak }
    ' "$work/time" >>"$work/runs"
}

echo "verify_cost: $(basename "$program") ($(du -m "$program" | cut -f1) MB), $rounds rounds; load before: $(uptime | sed 's/.*load average: //')"
for round in $(seq "$rounds"); do
    run check check "$program" --model "$model"
    run compensate compensate "$program" --model "$model" -o "$written"
    run verify verify "$program" "$written" --model "$model"
    run compensate--passes compensate --passes "$program" --model "$model" -o "$written"
    run verify--passes verify --passes "$program" "$written" --model "$model"
    echo "verify_cost: round $round done; load: $(uptime | sed 's/.*load average: //')"
done

# Medians of each command's CPU time and peak, and the ratios to check's CPU time.
sort -k1,1 -k2,2n "$work/runs" | awk -v rounds="$rounds" '
    { cpu[$1] = cpu[$1] " " $2; peak[$1] = peak[$1] " " $3 }
    function median(list,    n, v, i, j, t) {
        n = split(list, v, " ")
        for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (v[j] + 0 < v[i] + 0) { t = v[i]; v[i] = v[j]; v[j] = t }
        return v[int((n + 1) / 2)]
    }
    END {
        base = median(cpu["check"])
        printf "%-20s %10s %10s %12s   %s\n", "command", "CPU (s)", "x check", "peak (MB)", "CPU of each round (s)"
        split("check verify compensate verify--passes compensate--passes", names, " ")
        for (k = 1; k <= 5; k++) {
            name = names[k]
            c = median(cpu[name]); p = median(peak[name])
            printf "%-20s %10.2f %10.2f %12.0f  %s\n", name, c, c / base, p / 1024, cpu[name]
        }
    }
'
