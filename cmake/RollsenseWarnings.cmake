# rollsense_warnings(target): the project's warning set, on every target we build.
function(rollsense_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                           -Wold-style-cast -Wcast-align -Wnull-dereference)
  if(ROLLSENSE_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
