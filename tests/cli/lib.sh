# lib.sh — what every tests/cli script shares, sourced at its top:
#   check NAME 0|1 [DETAIL]   counts a check and prints PASS or FAIL NAME
#                             (with DETAIL in parentheses after a failure)
#   yes01 COMMAND...          prints 1 when the command succeeds, else 0
#                             (for check's second argument)
#   finish [LABEL]            prints the counts and returns 0 only when no
#                             check failed: a script's last line, so its
#                             status is the test's
# A script that sources it starts with pass=0 and fail=0.
pass=0
fail=0
check() {
    if [[ "$2" == 1 ]]; then
        pass=$((pass + 1))
        echo "PASS $1"
    else
        fail=$((fail + 1))
        echo "FAIL $1${3:+ ($3)}"
    fi
}
yes01() { if "$@"; then echo 1; else echo 0; fi; }
finish() {
    echo "${1:+$1: }$pass passed, $fail failed"
    ((fail == 0))
}
