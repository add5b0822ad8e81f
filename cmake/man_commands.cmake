# Run as `cmake -DRCDEM=... -DOUT=... -P man_commands.cmake`: writes a help2man include file with
# each command's --help, so that the man page documents every command's options, not only the list.
set(text "[COMMANDS]\n")
foreach(cmd generate run calibrate study print-schema)
  execute_process(COMMAND ${RCDEM} ${cmd} --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${RCDEM} ${cmd} --help failed")
  endif()
  string(REPLACE "${RCDEM}" "rcdem" help "${help}")
  # troff: a backslash is \e, and a line may not start with a period or an apostrophe.
  string(REPLACE "\\" "\\e" help "${help}")
  string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" help "${help}")
  string(APPEND text ".SS \"rcdem ${cmd}\"\n.nf\n${help}.fi\n")
endforeach()
file(WRITE ${OUT} "${text}")
