# Project-wide compiler options: warnings are errors, sanitizers on request.
add_library(sandtin_options INTERFACE)
target_compile_options(sandtin_options INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast -Wcast-align
  -Wunused -Woverloaded-virtual -Wdouble-promotion -Wformat=2
  -Werror)
# No fused multiply-adds unless written: a product is rounded before it is added, as in the
# SSE2 baseline, on every instruction set the physics dispatches to (AVX-512 has fused
# multiply-adds, and GCC's C++ default allows fusing), so results do not depend on the CPU
# (physics/talus_kernel_avx512.hpp).
target_compile_options(sandtin_options INTERFACE -ffp-contract=off)
# Clang's -Wdouble-promotion also flags float arguments passed to double parameters, which
# GCC (the reference compiler) accepts and which are exact; keep the GCC meaning.
if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  target_compile_options(sandtin_options INTERFACE -Wno-double-promotion)
endif()
# GCC 12 reports false -Wrestrict positives inside std::string at -O3 (GCC bug 105329).
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  target_compile_options(sandtin_options INTERFACE -Wno-restrict)
endif()

if(SANDTIN_SANITIZE AND SANDTIN_TSAN)
  message(FATAL_ERROR "SANDTIN_SANITIZE and SANDTIN_TSAN cannot be combined")
endif()
if(SANDTIN_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
if(SANDTIN_TSAN)
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()
if(SANDTIN_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "SANDTIN_FUZZ needs clang (libFuzzer): configure with CXX=clang++-14")
  endif()
  if(SANDTIN_TSAN)
    message(FATAL_ERROR "SANDTIN_FUZZ and SANDTIN_TSAN cannot be combined")
  endif()
  # Coverage instrumentation for every library; the fuzz targets add -fsanitize=fuzzer (main).
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer
    -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
