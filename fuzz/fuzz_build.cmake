# Included right after the top-level project() when configuring the fuzz build (see
# fuzz/CMakeLists.txt): every object of core/ and server/ gets libFuzzer's coverage
# instrumentation and AddressSanitizer + UndefinedBehaviorSanitizer, with no recovery from UB (a
# report stops the run as a crash); fuzz/CMakeLists.txt is read once the rest of the project is
# defined (a deferred include: the fuzz targets link the libraries of core/ and server/). -g1:
# line tables, all a report's stack trace needs (full debug info costs a third more compile time).
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "libFuzzer needs clang: configure with -DCMAKE_CXX_COMPILER=clang++-14")
endif()
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -g1)
add_link_options(-fsanitize=address,undefined)
# (Arguments of a deferred call are expanded when it runs, hence the variable.)
set(FOOTPOINT_FUZZ_DIR ${CMAKE_CURRENT_LIST_DIR})
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL include ${FOOTPOINT_FUZZ_DIR}/CMakeLists.txt)
