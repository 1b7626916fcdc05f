# scan_includes(OUT FILES... TOKENS...): appends to OUT every "#include" line of FILES that
# contains one of TOKENS, as "file: line". Shared by the include checks (shared_purity_check,
# codec_private_check). Call as scan_includes(bad "${files}" "${tokens}").
function(scan_includes out files tokens)
  set(found ${${out}})
  foreach(f ${files})
    file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include")
    foreach(line ${lines})
      foreach(token ${tokens})
        string(FIND "${line}" "${token}" pos)
        if(NOT pos EQUAL -1)
          list(APPEND found "${f}: ${line}")
        endif()
      endforeach()
    endforeach()
  endforeach()
  set(${out} ${found} PARENT_SCOPE)
endfunction()
