# The oracle's own tests (GoogleTest) and micro-benchmark. Included by the top-level
# CMakeLists.txt after add_subdirectory(oracle), where enable_testing() is in effect.
add_executable(oracle_test
  ${CMAKE_CURRENT_LIST_DIR}/tests/agreement_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tests/exact_2d_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tests/mesh_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tests/merged_mesh_limits_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tests/oracle_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tests/pixel_oracle_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tests/ray_oracle_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tests/ray_oracle_units_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tests/ray_plan_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tests/roof_triangulation_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tests/view_transform_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tests/witness_cover_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tests/witness_recheck_test.cpp)
target_link_libraries(oracle_test PRIVATE cullcheck_oracle GTest::gtest_main cullcheck_warnings)
add_test(NAME oracle_test COMMAND oracle_test)

if(TARGET benchmark::benchmark)
  add_executable(oracle_bench ${CMAKE_CURRENT_LIST_DIR}/bench_oracle.cpp ${CMAKE_CURRENT_LIST_DIR}/bench_exact_2d.cpp)
    # The benchmark (not the oracle) uses the generators for the CLI's default city.
  target_link_libraries(oracle_bench PRIVATE cullcheck_oracle cullcheck_generators benchmark::benchmark cullcheck_warnings)
  target_compile_options(oracle_bench PRIVATE $<$<CONFIG:RelWithDebInfo>:-O2>)  # timed loops: not the test files' -O1
endif()
