# One place for the project's warning flags.
function(hylo_set_warnings target)
  target_compile_options(${target} PRIVATE
    $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wno-sign-compare>)
endfunction()

# Declares a library folder as one target `hylo_<name>` with the alias `hylo::<name>`,
# its public headers under include/, installed and exported.
function(hylo_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES" ${ARGN})
  add_library(hylo_${name} ${ARG_SOURCES})
  add_library(hylo::${name} ALIAS hylo_${name})
  set_target_properties(hylo_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(hylo_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(hylo_${name} PUBLIC cxx_std_17)
  hylo_set_warnings(hylo_${name})
  install(TARGETS hylo_${name} EXPORT hyloTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()
