# SPDX-FileCopyrightText: 2026 The xeno authors
# SPDX-License-Identifier: MIT
#
# Runs xeno_query on one input and checks its exit status and standard error
# (ctest: query.directory_input, query.missing_input).
#   cmake -DTOOL=<xeno_query> -DINPUT=<path> -DSTATUS=<n> -DMESSAGE=<regex> -P check_exit.cmake
# Passes when the exit status is STATUS and stderr matches MESSAGE.
foreach(var TOOL INPUT STATUS MESSAGE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_exit.cmake: -D${var}=... is required")
  endif()
endforeach()

execute_process(COMMAND ${TOOL} ${INPUT} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status STREQUAL "${STATUS}")
  message(FATAL_ERROR "exit status ${status}, expected ${STATUS}; stderr:\n${err}")
endif()
if(NOT err MATCHES "${MESSAGE}")
  message(FATAL_ERROR "stderr does not match '${MESSAGE}':\n${err}")
endif()
