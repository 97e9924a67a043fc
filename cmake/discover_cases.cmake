# Run after a test executable is built (POST_BUILD): ask it for its cases
# (`<exe> --list`) and write a ctest file that registers each case as the
# entry <module>.<case>, so that one failing case can be rerun alone
# (`ctest -R '^plan\.dfs_column$'`) and ctest -j spreads the cases of one
# module over the cores.
#
# OPENBLAS_NUM_THREADS=1: CLP links OpenBLAS, whose idle thread pool makes
# every munmap a cross-CPU TLB shootdown (ASan unmaps CLP's large
# per-solve buffers): 4x slower sanitizer runs with the pool.
#
# LSAN_SUPP (sanitizer builds): LeakSanitizer's suppressions file, for the
# leaks of system libraries (tests/lsan.supp).
#
# Inputs (-D): EXE, MODULE, OUT, TIMEOUT, LSAN_SUPP (may be empty).
execute_process(COMMAND "${EXE}" --list OUTPUT_VARIABLE cases RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${EXE} --list failed (${rc})")
endif()
string(REPLACE "\n" ";" cases "${cases}")
set(env "OPENBLAS_NUM_THREADS=1")
if(LSAN_SUPP)
  set(env "${env};LSAN_OPTIONS=suppressions=${LSAN_SUPP}")
endif()
set(text "")
foreach(c ${cases})
  if(c STREQUAL "")
    continue()
  endif()
  string(APPEND text "add_test([=[${MODULE}.${c}]=] [=[${EXE}]=] [=[${c}]=])\n")
  string(APPEND text "set_tests_properties([=[${MODULE}.${c}]=] PROPERTIES TIMEOUT ${TIMEOUT} LABELS ${MODULE} ENVIRONMENT \"${env}\")\n")
endforeach()
file(WRITE "${OUT}" "${text}")
