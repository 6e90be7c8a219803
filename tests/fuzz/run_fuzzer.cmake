# SPDX-FileCopyrightText: 2026 The xeno authors
# SPDX-License-Identifier: MIT
#
# Runs a libFuzzer binary for SECONDS seconds on a fresh copy of the seed corpus CORPUS made in
# WORK_DIR (the repository's corpus is never written), with a 10 s limit per input; crash files
# go to WORK_DIR. Passes when the fuzzer exits 0 (it exits non-zero on a crash, a leak, a
# sanitizer report or an input slower than 10 s).
# Usage: cmake -DFUZZER=<exe> -DCORPUS=<dir> -DWORK_DIR=<dir> [-DSECONDS=30] -P run_fuzzer.cmake
if(NOT FUZZER OR NOT CORPUS OR NOT WORK_DIR)
  message(FATAL_ERROR "run_fuzzer.cmake: set -DFUZZER, -DCORPUS and -DWORK_DIR")
endif()
if(NOT SECONDS)
  set(SECONDS 30)
endif()
file(REMOVE_RECURSE ${WORK_DIR}/corpus)
file(MAKE_DIRECTORY ${WORK_DIR}/corpus ${WORK_DIR}/artifacts)
file(GLOB seeds ${CORPUS}/*)
if(seeds)
  file(COPY ${seeds} DESTINATION ${WORK_DIR}/corpus)
endif()
execute_process(
  COMMAND ${FUZZER} -max_total_time=${SECONDS} -timeout=10 -print_final_stats=1
          -artifact_prefix=${WORK_DIR}/artifacts/ ${WORK_DIR}/corpus
  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
# libFuzzer reports on stderr; keep the summary lines (runs, executions per second, coverage).
string(REGEX MATCHALL "(#[0-9]+[^\n]*DONE[^\n]*|stat::[^\n]*|Done [0-9]+ runs[^\n]*)" summary "${err}")
string(REPLACE ";" "\n" summary "${summary}")
if(NOT code EQUAL 0)
  message(FATAL_ERROR "${FUZZER} failed (${code}); inputs in ${WORK_DIR}/artifacts\n${err}")
endif()
message(STATUS "${FUZZER}: no crash in ${SECONDS} s\n${summary}")
