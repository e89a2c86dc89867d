#!/usr/bin/env bash
# The shadowvol program as a user meets it: `bench --quick` runs every row,
# checks every call against the reference and exits 0; bad arguments get a
# message on stderr and exit status 2; --help goes to stdout with status 0.
# usage: check_cli.sh PATH/TO/shadowvol
set -u
sv="$1"
fail=0
err() { echo "FAIL: $*"; fail=1; }

out=$("$sv" bench --quick 2>/tmp/sv_cli_err.$$); rc=$?
[ $rc -eq 0 ] || err "bench --quick exited $rc: $(cat /tmp/sv_cli_err.$$)"
rows=$(printf '%s\n' "$out" | grep -cE '^(count_facing|count_facing_cull|create_sil_triangles|create_cap_triangles|create_shadow_volume|create_shadow_volume_cull) ')
okrows=$(printf '%s\n' "$out" | grep -E '^(count_facing|create_)' | grep -cE '\| ok$')
# 6 routines x 3 variants x 2 regimes
[ "$rows" -ge 36 ] || err "expected at least 36 table rows, got $rows"
[ "$rows" -eq "$okrows" ] || err "$((rows - okrows)) rows not checked ok"
printf '%s\n' "$out" | grep -q 'FAILED' && err "a row FAILED its correctness check"
printf '%s\n' "$out" | grep -q '^timer' || err "no timer line in the header"

expect_status() { # expected-status description args...
  local want=$1; shift; local what=$1; shift
  "$sv" "$@" >/tmp/sv_cli_out.$$ 2>/tmp/sv_cli_err.$$; local got=$?
  [ $got -eq "$want" ] || err "$what: exit $got, want $want"
  if [ "$want" -ne 0 ]; then
    [ -s /tmp/sv_cli_err.$$ ] || err "$what: no message on stderr"
  else
    [ -s /tmp/sv_cli_out.$$ ] || err "$what: nothing on stdout"
  fi
}
expect_status 0 "help" help
expect_status 0 "--help" --help
expect_status 0 "bench --help" bench --help
expect_status 2 "no command"
expect_status 2 "unknown command" frobnicate
expect_status 2 "unknown option" bench --frobnicate
expect_status 2 "--runs 0" bench --runs 0
expect_status 2 "--runs abc" bench --runs abc
expect_status 2 "--regime foo" bench --regime foo
expect_status 2 "unknown routine" bench --routine no_such_routine
expect_status 2 "unknown variant" bench --variant no_such_variant
expect_status 2 "--timer foo" bench --timer foo

rm -f /tmp/sv_cli_out.$$ /tmp/sv_cli_err.$$
[ $fail -eq 0 ] && echo "shadowvol CLI: $rows rows checked ok, argument errors and help behave"
exit $fail
