# Project-wide compiler options: warnings are errors, sanitizers on request.
add_library(sandtin_options INTERFACE)
target_compile_options(sandtin_options INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast -Wcast-align
  -Wunused -Woverloaded-virtual -Wdouble-promotion -Wformat=2
  -Werror)
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
