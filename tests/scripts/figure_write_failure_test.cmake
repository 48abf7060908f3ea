# A figure program that cannot write its data fails loudly (figures/support/
# figure_file.hpp): run by CTest as
#   cmake -DFIGURE=<fig_ch06_drift> -DNAME=ch06_drift.dat -DWORK=<folder> -P this file
# Into a folder that exists the file is written; into one that does not, the program
# exits non-zero with a message naming the file, and writes nothing. EMULATOR (a list,
# optional) runs the program in a cross build.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/good)
execute_process(COMMAND ${EMULATOR} ${FIGURE} ${WORK}/good RESULT_VARIABLE status
                OUTPUT_QUIET)
if(NOT status EQUAL 0 OR NOT EXISTS ${WORK}/good/${NAME})
  message(FATAL_ERROR "${FIGURE} did not write ${NAME} into a good folder (${status})")
endif()
file(SIZE ${WORK}/good/${NAME} size)
if(size EQUAL 0)
  message(FATAL_ERROR "${FIGURE} wrote an empty ${NAME}")
endif()
execute_process(COMMAND ${EMULATOR} ${FIGURE} ${WORK}/missing RESULT_VARIABLE status
                OUTPUT_QUIET ERROR_VARIABLE message)
if(status EQUAL 0)
  message(FATAL_ERROR "${FIGURE} exited 0 although ${WORK}/missing does not exist")
endif()
if(NOT message MATCHES "missing/${NAME}: cannot write")
  message(FATAL_ERROR "the message does not name ${NAME}: ${message}")
endif()
if(EXISTS ${WORK}/missing)
  message(FATAL_ERROR "${FIGURE} created ${WORK}/missing")
endif()
message(STATUS "${FIGURE}: a failed write is an error naming ${NAME}")
