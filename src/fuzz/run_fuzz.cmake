# Runs the scene-loader fuzzer for SECONDS seconds on a corpus seeded with the shipped
# scenes (cmake -DFUZZER=... -DSEEDS=... -DCORPUS=... -DSECONDS=... -P run_fuzz.cmake).
# Any crash, sanitizer report or leak makes libFuzzer exit non-zero, and so this script.
file(MAKE_DIRECTORY ${CORPUS})
file(GLOB seeds ${SEEDS}/*.toml)
file(COPY ${seeds} DESTINATION ${CORPUS})
execute_process(
  COMMAND ${FUZZER} -max_total_time=${SECONDS} -max_len=8192 -rss_limit_mb=2048
          -timeout=10 -print_final_stats=1 ${CORPUS}
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "fuzz_scene found a failing input (exit ${result}); see crash-* "
                      "in the working folder")
endif()
