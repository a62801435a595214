# ctest script: installs the current build into a scratch prefix, then configures, builds and
# runs tests/consumer against it with find_package(hylo).
set(prefix "${BUILD_DIR}/consumer_test/prefix")
set(consumer_build "${BUILD_DIR}/consumer_test/build")
file(REMOVE_RECURSE "${BUILD_DIR}/consumer_test")
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()
run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}" -B "${consumer_build}" -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build "${consumer_build}")
run(${CMAKE_COMMAND} -E env "LD_LIBRARY_PATH=${prefix}/lib" "${consumer_build}/consumer")
message(STATUS "consumer built and ran against ${prefix}")
