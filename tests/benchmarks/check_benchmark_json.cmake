# cmake -DBENCHMARK=<exe> -DJSON=<out.json> [-DKEYS=section:key;...] -P check_benchmark_json.cmake
# Runs the benchmark with --quick and fails unless it exits 0 and its JSON parses and holds
# every section and key the report promises (KEYS, default: the ikd-tree benchmark's). A
# benchmark on real data that is absent prints so and writes no JSON: reported as skipped
# through the test's SKIP_REGULAR_EXPRESSION.
file(REMOVE ${JSON})
execute_process(COMMAND ${BENCHMARK} --quick --json ${JSON} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "benchmark exited with ${rc}")
endif()
if(NOT EXISTS ${JSON})
  message(STATUS "no JSON written: ${JSON}")
  return()
endif()
file(READ ${JSON} text)
set(expected
  "workload1_build:ikd_tree_ms" "workload1_build:nanoflann_ms" "workload1_build:pcl_ms"
  "workload1_build:ikd_tree_heap_bytes_per_point"
  "workload2_knn5:ikd_tree_ns_per_query" "workload2_knn5:nanoflann_ns_per_query"
  "workload2_knn5:pcl_ns_per_query"
  "workload3_lidar:ikd_step_ms_mean" "workload3_lidar:nanoflann_rebuild_ms_at_max_map"
  "workload3_lidar:pcl_rebuild_ms_at_max_map" "workload3_lidar:disagreements_with_static_trees"
  "targets:knn5_ikd_over_nanoflann" "targets:step_speedup_vs_nanoflann_rebuild"
  "targets:ikd_bytes_per_point_1m_build")
if(DEFINED KEYS)
  set(expected ${KEYS})
endif()
foreach(entry IN LISTS expected)
  string(REPLACE ":" ";" parts ${entry})
  list(GET parts 0 section)
  list(GET parts 1 key)
  string(JSON value ERROR_VARIABLE error GET "${text}" ${section} ${key})
  if(error)
    message(FATAL_ERROR "${JSON}: ${section}.${key}: ${error}")
  endif()
  if(NOT value MATCHES "^-?[0-9]")
    message(FATAL_ERROR "${JSON}: ${section}.${key} is not a number: ${value}")
  endif()
endforeach()
message(STATUS "benchmark JSON ok: ${JSON}")
