# Sourced by the harness's shell tests: `check NAME EXPECTED_CODE ACTUAL_CODE [OUTPUT_FILE PATTERN]`
# counts a check as passed when the exit code is the expected one and the output matches; `finish`
# prints the counts and fails when any check failed.
pass=0; fail=0
check() {
    local name=$1 want=$2 got=$3
    if [ "$got" != "$want" ]; then
        echo "FAIL $name: exit $got, expected $want"; [ -n "${4:-}" ] && sed 's/^/    /' "$4"; fail=$((fail + 1)); return
    fi
    if [ -n "${4:-}" ] && ! grep -qE "$5" "$4"; then
        echo "FAIL $name: output lacks /$5/:"; sed 's/^/    /' "$4"; fail=$((fail + 1)); return
    fi
    echo "ok   $name"; pass=$((pass + 1))
}
finish() {
    echo "$pass passed, $fail failed"
    [ "$fail" -eq 0 ]
}
