#!/usr/bin/env bash
# Coverage-guided fuzzing (cargo fuzz / libFuzzer) of every parser botsim takes input through:
#   asm     the KCPSM6 assembler (+ every output format, disassembly round trip)
#   image   program images: .hex, .mem, Xilinx-template and behavioural .v
#   world   world maps: .txt, .coe, .mem, .png (+ round trip through the same format)
#   script  motor scripts
# Usage: scripts/dev/fuzz.sh [SECONDS-PER-TARGET] [TARGET...]   (default 60 s, all targets)
# The corpus grows in fuzz/corpus/TARGET (seeded from fuzz/seeds/TARGET); a finding is written
# to fuzz/artifacts/TARGET and makes the script fail. Keep reproducers in fuzz/regressions/
# TARGET: core/tests/fuzz_corpus.rs replays them and the corpora in every `cargo test`. The
# committed corpora are minimised (`cargo fuzz cmin`) and keep the inputs of up to 4 KB.
# Needs cargo-fuzz (`cargo install cargo-fuzz`); stable Rust runs it with RUSTC_BOOTSTRAP=1.
set -euo pipefail
cd "$(dirname "$0")/../.."
secs=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(asm image world script)
command -v cargo-fuzz >/dev/null || { echo "fuzz: cargo-fuzz is not installed: cargo install cargo-fuzz" >&2; exit 1; }
export RUSTC_BOOTSTRAP=1
cargo fuzz build -s none >/dev/null
for t in "${targets[@]}"; do
    mkdir -p "fuzz/corpus/$t" "fuzz/artifacts/$t"
    log="fuzz/artifacts/$t/last-run.log"
    # -timeout: one input taking over 10 s is a hang; -max_len: a 4K-line program or a map.
    if ! cargo fuzz run -s none "$t" "fuzz/corpus/$t" "fuzz/seeds/$t" -- \
        -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
        -print_final_stats=1 >"$log" 2>&1; then
        echo "fuzz: $t: FINDING (see $log and fuzz/artifacts/$t)" >&2
        tail -30 "$log" >&2
        exit 1
    fi
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1)
    echo "fuzz: $t: $runs executions in ${secs}s, $cov, corpus $(ls "fuzz/corpus/$t" | wc -l) files, no finding"
done
