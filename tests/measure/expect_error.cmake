# One bad-input case of a measure tool:
#   cmake -DTOOL=path "-DARGS=a b" -DSTATUS=n "-DMESSAGE=text" -P expect_error.cmake
# Passes when the tool exits with STATUS and its stderr is one line containing MESSAGE.
separate_arguments(args UNIX_COMMAND "${ARGS}")
execute_process(COMMAND ${TOOL} ${args} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(STRIP "${err}" line)
string(FIND "${line}" "\n" newline)
string(FIND "${line}" "${MESSAGE}" at)
if(NOT status STREQUAL "${STATUS}" OR NOT newline EQUAL -1 OR at EQUAL -1 OR NOT out STREQUAL "")
  message(FATAL_ERROR "${TOOL} ${ARGS}: expected exit ${STATUS} and one line with '${MESSAGE}'; "
                      "got exit ${status}, stderr '${err}', stdout '${out}'")
endif()
