# Runs PROGRAM with the argument "default" and checks that xeno's default error handler printed
# the message and aborted (a non-zero exit), rather than carrying on with bad input.
execute_process(COMMAND ${PROGRAM} default RESULT_VARIABLE result ERROR_VARIABLE err OUTPUT_VARIABLE out)
if(result EQUAL 0)
  message(FATAL_ERROR "expected an abort, got exit 0; stdout: ${out}")
endif()
if(NOT err MATCHES "xeno: Box: half_extents.x must be finite and > 0 \\(got -1\\)")
  message(FATAL_ERROR "expected the error message on stderr, got: ${err}")
endif()
if(out MATCHES "continued")
  message(FATAL_ERROR "the program continued after the error")
endif()
message(STATUS "aborted as expected (${result}) with: ${err}")
