# Runs one libFuzzer target for SECONDS seconds on a corpus seeded with the files
# SEEDS/PATTERN (cmake -DFUZZER=... -DSEEDS=... -DPATTERN=... -DCORPUS=... -DSECONDS=...
# -P run_fuzz.cmake). Any crash, sanitizer report, leak, timeout or exception other than
# exactpixels::Error makes libFuzzer exit non-zero, and so this script.
file(MAKE_DIRECTORY ${CORPUS})
file(GLOB seeds ${SEEDS}/${PATTERN})
file(COPY ${seeds} DESTINATION ${CORPUS})
execute_process(
  COMMAND ${FUZZER} -max_total_time=${SECONDS} -max_len=8192 -rss_limit_mb=2048
          -timeout=10 -print_final_stats=1 ${CORPUS}
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  get_filename_component(name ${FUZZER} NAME)
  message(FATAL_ERROR "${name} found a failing input (exit ${result}); see crash-* "
                      "in the working folder")
endif()
