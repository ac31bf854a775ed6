# rollsense_warnings(target): the project's warning set, on every target we build.
# (-Wnull-dereference is left out: GCC 12 reports false positives inside libstdc++.)
function(rollsense_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                           -Wold-style-cast -Wcast-align)
  if(ROLLSENSE_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
