# The kit zips are all or nothing (src/kits/zip_atomically.cmake): run by CTest as
#   cmake -DSCRIPT=src/kits/zip_atomically.cmake -DWORK=<empty folder> -P this file
# A good zip is made; then a zip that tar cannot finish (an entry that does not exist)
# must fail, leave the good zip byte for byte as it was and no temporary file behind.
include(${SCRIPT})
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/kit)
file(WRITE ${WORK}/kit/a.txt "first file\n")
file(WRITE ${WORK}/kit/b.txt "second file\n")

zip_atomically(ZIP ${WORK}/kit.zip DIRECTORY ${WORK} ENTRIES kit RESULT_VARIABLE problem)
if(problem OR NOT EXISTS ${WORK}/kit.zip)
  message(FATAL_ERROR "a good zip was not made: ${problem}")
endif()
file(SHA256 ${WORK}/kit.zip good)

# Proof that the check can fail: tar writing the target directly leaves a partial zip.
execute_process(COMMAND ${CMAKE_COMMAND} -E tar cf direct.zip --format=zip kit missing
                WORKING_DIRECTORY ${WORK} RESULT_VARIABLE status OUTPUT_QUIET ERROR_QUIET)
if(status EQUAL 0)
  message(FATAL_ERROR "tar of a missing entry succeeded; the test below proves nothing")
endif()
if(NOT EXISTS ${WORK}/direct.zip)
  message(FATAL_ERROR "tar left no partial zip; the test below proves nothing new")
endif()

zip_atomically(ZIP ${WORK}/kit.zip DIRECTORY ${WORK} ENTRIES kit missing
               RESULT_VARIABLE problem)
if(NOT problem)
  message(FATAL_ERROR "zipping a missing entry reported success")
endif()
file(SHA256 ${WORK}/kit.zip after)
if(NOT after STREQUAL good)
  message(FATAL_ERROR "the failed zip replaced the good one")
endif()
file(GLOB leftovers ${WORK}/.kit.zip.*)
if(leftovers)
  message(FATAL_ERROR "temporary files left behind: ${leftovers}")
endif()

# A zip that succeeds replaces the old one.
file(WRITE ${WORK}/kit/c.txt "third file\n")
zip_atomically(ZIP ${WORK}/kit.zip DIRECTORY ${WORK} ENTRIES kit RESULT_VARIABLE problem)
file(SHA256 ${WORK}/kit.zip replaced)
if(problem OR replaced STREQUAL good)
  message(FATAL_ERROR "a good second zip did not replace the first: ${problem}")
endif()
message(STATUS "zip_atomically: failure keeps the old zip, success replaces it")
