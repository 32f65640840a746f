# Runs PROGRAM with each of the bad VALUES (a ;-list) of --OPTION=: each must exit with code 2 and
# name the option on stderr.
foreach(value IN LISTS VALUES)
  execute_process(COMMAND ${PROGRAM} --${OPTION}=${value} --benchmark_filter=^$
                  RESULT_VARIABLE code ERROR_VARIABLE message OUTPUT_QUIET)
  if(NOT code EQUAL 2 OR NOT message MATCHES "--${OPTION}: expected a whole number")
    message(FATAL_ERROR "--${OPTION}=${value}: exit code ${code}, stderr: ${message}")
  endif()
endforeach()
