# igaparam_last_json_line(<text> <variable>): sets <variable> to the last non-empty line of
# <text>, which must be a JSON object (else a fatal error). Shared by the test scripts.
function(igaparam_last_json_line text variable)
  string(STRIP "${text}" text)
  string(REGEX REPLACE "^.*\n" "" json "${text}")
  if(NOT json MATCHES "^{.*}$")
    message(FATAL_ERROR "the last line of the output is not a JSON object: ${json}")
  endif()
  set(${variable} "${json}" PARENT_SCOPE)
endfunction()
