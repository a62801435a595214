# HYLO_BUILD_FUZZERS: libFuzzer targets (tests/fuzz) for every reader of outside data. The
# whole build is instrumented: coverage for libFuzzer (-fsanitize=fuzzer-no-link) plus
# AddressSanitizer and UndefinedBehaviorSanitizer, with UB reports fatal so that libFuzzer
# keeps the input. Clang only (libFuzzer ships with clang). scripts/fuzz.sh configures it.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "HYLO_BUILD_FUZZERS needs clang (libFuzzer); configure with "
    "-DCMAKE_CXX_COMPILER=clang++ (scripts/fuzz.sh does)")
endif()
set(hylo_fuzz_sanitizers -fsanitize=address,undefined -fno-sanitize-recover=all
  -fno-omit-frame-pointer)
add_compile_options(-fsanitize=fuzzer-no-link ${hylo_fuzz_sanitizers} -g)
add_link_options(${hylo_fuzz_sanitizers})
