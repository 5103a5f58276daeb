# occsim_set_warnings(target): the project's warning policy, one place for every target.
function(occsim_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                           -Wcast-align)
  if(OCCSIM_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
