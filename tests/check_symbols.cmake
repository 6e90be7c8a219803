# SPDX-FileCopyrightText: 2026 The xeno authors
# SPDX-License-Identifier: MIT
#
# Reads an object file's symbols (nm -C) and checks compiled mode left the heavy templates to the
# library: each of UNDEFINED ("|"-separated) appears as an undefined symbol, and no defined symbol
# contains NOT_DEFINED.
# Usage: cmake -DNM=<nm> -DOBJECT=<file.o> -DUNDEFINED="a|b" -DNOT_DEFINED=<text> -P check_symbols.cmake
execute_process(COMMAND ${NM} -C ${OBJECT} OUTPUT_VARIABLE symbols RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "${NM} failed on ${OBJECT}")
endif()
string(REPLACE "|" ";" undefined "${UNDEFINED}")
foreach(name IN LISTS undefined)
  string(FIND "${symbols}" " U ${name}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${name} is not undefined in ${OBJECT}: this file compiled it instead of taking it from the library")
  endif()
endforeach()
string(REPLACE "\n" ";" lines "${symbols}")
foreach(line IN LISTS lines)
  if(line MATCHES " [TtWw] " AND line MATCHES "${NOT_DEFINED}")
    message(FATAL_ERROR "defined in ${OBJECT}, expected from the library: ${line}")
  endif()
endforeach()
