# voxspan_warnings(<target>): the project's warning set; errors when VOXSPAN_WERROR is on.
function(voxspan_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
    -Wnon-virtual-dtor -Woverloaded-virtual -Wimplicit-fallthrough
    $<$<BOOL:${VOXSPAN_WERROR}>:-Werror>)
endfunction()
