# mutate-lib.sh: the loop shared by the mutation scripts (sourced, not run).
#   mutate FILE FILTER TEST-ARGS... -- "name|sed expression"...
# applies each mutation to FILE alone, runs `cargo test --workspace --release --no-fail-fast TEST-ARGS`,
# reports CAUGHT (with the failing tests), MISSED, BUILD FAILS or NOT APPLIED, and restores FILE.
mutate() {
  local file=$1 filter=$2
  shift 2
  local tests=()
  while [ "$1" != "--" ]; do tests+=("$1"); shift; done
  shift
  local orig
  orig=$(mktemp)
  cp "$file" "$orig"
  trap 'cp "'"$orig"'" "'"$file"'"' EXIT
  local m name expr out failed
  for m in "$@"; do
    name=${m%%|*}
    expr=${m#*|}
    [[ -n "$filter" && "$name" != *$filter* ]] && continue
    cp "$orig" "$file"
    sed -i "$expr" "$file"
    if cmp -s "$file" "$orig"; then
      echo "NOT APPLIED  $name"
      continue
    fi
    out=$(cargo test --workspace --release --no-fail-fast "${tests[@]}" 2>&1)
    failed=$(echo "$out" | grep -E '^test .* FAILED$' | sed -E 's/^test (.*) \.\.\. FAILED/\1/' | tr '\n' ' ')
    if echo "$out" | grep -q "does not assemble\|could not compile\|failed to run custom build"; then
      echo "BUILD FAILS  $name"
    elif [ -n "$failed" ]; then
      echo "CAUGHT       $name: $failed"
    else
      echo "MISSED       $name"
    fi
  done
  cp "$orig" "$file"
}
