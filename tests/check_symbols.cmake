# SPDX-FileCopyrightText: 2026 The xeno authors
# SPDX-License-Identifier: MIT
#
# Reads an object file's symbols (nm -C) and checks which templates it compiled: each of UNDEFINED
# ("|"-separated) appears as an undefined symbol (compiled mode left it to the library), each of
# DEFINED as a defined one (the file compiled it), and no defined symbol matches the regular
# expression NOT_DEFINED.
# Usage: cmake -DNM=<nm> -DOBJECT=<file.o> [-DUNDEFINED="a|b"] [-DDEFINED="c|d"] -DNOT_DEFINED=<regex> -P check_symbols.cmake
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
string(REPLACE "|" ";" defined "${DEFINED}")
foreach(name IN LISTS defined)
  set(found FALSE)
  foreach(line IN LISTS lines)
    string(FIND "${line}" "${name}" at)
    if(line MATCHES " [TtWw] " AND NOT at EQUAL -1)
      set(found TRUE)
    endif()
  endforeach()
  if(NOT found)
    message(FATAL_ERROR "${name} is not defined in ${OBJECT}: the file does not compile what the check is about")
  endif()
endforeach()
foreach(line IN LISTS lines)
  if(line MATCHES " [TtWw] " AND line MATCHES "${NOT_DEFINED}")
    message(FATAL_ERROR "defined in ${OBJECT}, where it should not be compiled: ${line}")
  endif()
endforeach()
