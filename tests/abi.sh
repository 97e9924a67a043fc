#!/bin/bash
# The shared library's ABI is exactly the public headers' US_API
# declarations: every exported function symbol is declared with US_API in
# include/unstack/*.h, and every such declaration is exported.
# Usage: abi.sh <libunstack.so> <include dir>
set -u
lib=$1 inc=$2
exported=$(nm -D --defined-only "$lib" | awk '$2 == "T" {print $3}' | sort -u)
declared=$(grep -ho 'US_API[^(]*\bus_[A-Za-z0-9_]*(' "$inc"/unstack/*.h |
           grep -o 'us_[A-Za-z0-9_]*($' | tr -d '(' | sort -u)
nexp=$(echo "$exported" | grep -c .)
ndec=$(echo "$declared" | grep -c .)
extra=$(comm -23 <(echo "$exported") <(echo "$declared"))
missing=$(comm -13 <(echo "$exported") <(echo "$declared"))
fail=0
if [ -n "$extra" ]; then echo "exported but not public API:"; echo "$extra" | sed 's/^/  /'; fail=1; fi
if [ -n "$missing" ]; then echo "declared US_API but not exported:"; echo "$missing" | sed 's/^/  /'; fail=1; fi
if [ "$ndec" -lt 50 ]; then echo "only $ndec US_API declarations found"; fail=1; fi
echo "$nexp exported, $ndec declared"
exit $fail
