# SPDX-FileCopyrightText: 2026 The xeno authors
# SPDX-License-Identifier: MIT
#
# Runs PROGRAM twice, as two processes (or PROGRAM then OTHER), and fails unless both exit 0 with
# identical, non-empty output: the cross-process half of the determinism test, and header-only
# against compiled mode, one worker against several (docs/robustness.md, "Determinism").
# Usage: cmake -DPROGRAM=<xeno_determinism> [-DOTHER=<program>] [-DOTHER_ARGS="<arguments of the
#        second run>"] [-DWORK_DIR=<dir>] -P compare_runs.cmake
if(NOT PROGRAM)
  message(FATAL_ERROR "compare_runs.cmake: set -DPROGRAM=<executable>")
endif()
set(program_1 ${PROGRAM})
set(program_2 ${PROGRAM})
if(OTHER)
  set(program_2 ${OTHER})
endif()
set(args_1 "")
separate_arguments(args_2 UNIX_COMMAND "${OTHER_ARGS}")
foreach(run 1 2)
  execute_process(COMMAND ${program_${run}} ${args_${run}} RESULT_VARIABLE code OUTPUT_VARIABLE out_${run} ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "run ${run} (${program_${run}}) failed (${code}): ${err}")
  endif()
endforeach()
if(out_1 STREQUAL "")
  message(FATAL_ERROR "${PROGRAM} printed nothing")
endif()
if(NOT out_1 STREQUAL out_2)
  if(WORK_DIR)
    file(WRITE ${WORK_DIR}/determinism_run1.txt "${out_1}")
    file(WRITE ${WORK_DIR}/determinism_run2.txt "${out_2}")
  endif()
  message(FATAL_ERROR "the two runs gave different state hashes:\n--- run 1\n${out_1}--- run 2\n${out_2}")
endif()
message(STATUS "the two runs agree:\n${out_1}")
