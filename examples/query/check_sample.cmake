# SPDX-FileCopyrightText: 2026 The xeno authors
# SPDX-License-Identifier: MIT
#
# Runs xeno_query on the sample file and checks its answer (ctest: query.sample_pairs).
#   cmake -DTOOL=<xeno_query> -DINPUT=<sample_pairs.tsv> -DEXPECTED=<sample_pairs.expected>
#         -DBAD_LINES=<n;m> -P check_sample.cmake
# Passes when stdout equals EXPECTED byte for byte, the exit status is 1 and stderr names every
# line in BAD_LINES as "line <n>:" and no other line. The expected file was written by the tool
# on x86-64 (SSE2 arithmetic, g++ and clang++ agree); regenerate it with
#   xeno_query --precision double sample_pairs.tsv > sample_pairs.expected
# after a change to the narrow phase, and check the new numbers before committing them.
foreach(var TOOL INPUT EXPECTED BAD_LINES)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_sample.cmake: -D${var}=... is required")
  endif()
endforeach()

execute_process(COMMAND ${TOOL} --precision double ${INPUT}
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(READ ${EXPECTED} expected)

set(failed FALSE)
if(NOT out STREQUAL expected)
  message(SEND_ERROR "stdout differs from ${EXPECTED}\n--- got:\n${out}--- expected:\n${expected}")
  set(failed TRUE)
endif()
if(NOT status STREQUAL "1")
  message(SEND_ERROR "exit status ${status}, expected 1 (the sample has bad lines)")
  set(failed TRUE)
endif()
string(REGEX MATCHALL "line [0-9]+:" named "${err}")
set(expected_named "")
foreach(n IN LISTS BAD_LINES)
  list(APPEND expected_named "line ${n}:")
endforeach()
if(NOT named STREQUAL expected_named)
  message(SEND_ERROR "stderr names '${named}', expected '${expected_named}':\n${err}")
  set(failed TRUE)
endif()
if(NOT failed)
  message(STATUS "xeno_query sample: output, exit status and bad lines as expected\n${err}")
endif()
