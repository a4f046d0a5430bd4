# MECHSIM_SANITIZE: every target built with AddressSanitizer (+ LeakSanitizer) and
# UndefinedBehaviorSanitizer; any UB report aborts (-fno-sanitize-recover). MECHSIM_FUZZ adds
# libFuzzer's coverage instrumentation and the targets under tests/fuzz (docs/testing.md).
# Both need clang (libFuzzer and -fsanitize=fuzzer are clang's); the default build stays on g++.
if(MECHSIM_FUZZ AND NOT MECHSIM_SANITIZE)
  message(STATUS "MECHSIM_FUZZ implies MECHSIM_SANITIZE")
  set(MECHSIM_SANITIZE ON CACHE BOOL "" FORCE)
endif()
if(MECHSIM_SANITIZE)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang" OR NOT CMAKE_C_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "MECHSIM_SANITIZE/MECHSIM_FUZZ need clang: configure a fresh build dir with "
                        "CC=clang CXX=clang++ (apt-get install clang libclang-rt-14-dev)")
  endif()
  set(mechsim_sanitize_flags -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  add_compile_options(${mechsim_sanitize_flags})
  add_link_options(${mechsim_sanitize_flags})
endif()
if(MECHSIM_FUZZ)
  # Coverage counters in the code under test; only the fuzz targets link libFuzzer itself
  # (-fsanitize=fuzzer, tests/fuzz/CMakeLists.txt), the other executables keep their main().
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
