# Warnings and sanitizers per target, never global flags.
function(eco_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow -Wconversion -Wno-sign-conversion)
  if(ECO_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=all -O1)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
  if(ECO_FUZZ)  # coverage for libFuzzer; the fuzz executables add -fsanitize=fuzzer at link
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
endfunction()
