#!/usr/bin/env bash
# ctest registers every unit test case by its name (catch_discover_tests), and a ';' in a name
# splits it into two tests that match no case, so the case never runs in the suite and passes
# unseen. No name may hold one.
#   test_names.sh MESHFREE_TESTS
set -eu
# (Catch2 lists with an exit status of the number of cases: not an error.)
names="$("$1" --list-test-names-only || true)"
[ -n "$names" ] || { echo "FAIL: $1 listed no test cases"; exit 1; }
split="$(grep -F ';' <<<"$names" || true)"
[ -z "$split" ] || { echo "FAIL: test case names with ';' (ctest would never run them):"; echo "$split"; exit 1; }
echo "ok: $(grep -c . <<<"$names") test case names, none with ';'"
