# Runs PROGRAM with bad --seeds values: each must exit with code 2 and name the option on stderr.
foreach(value abc 0 -1 3x "")
  execute_process(COMMAND ${PROGRAM} --seeds=${value} --benchmark_filter=^$
                  RESULT_VARIABLE code ERROR_VARIABLE message OUTPUT_QUIET)
  if(NOT code EQUAL 2 OR NOT message MATCHES "--seeds: expected a whole number")
    message(FATAL_ERROR "--seeds=${value}: exit code ${code}, stderr: ${message}")
  endif()
endforeach()
