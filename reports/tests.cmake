# Tests of the report libraries written next to them (GoogleTest). Included by
# properties/CMakeLists.txt, where enable_testing() is in effect.
add_executable(pictures_test ${CMAKE_CURRENT_LIST_DIR}/tests/pictures_test.cpp)
target_link_libraries(pictures_test PRIVATE cullcheck_pictures GTest::gtest_main cullcheck_warnings)
add_test(NAME pictures_test COMMAND pictures_test)

# The gate's verdict and its JUnit XML, from verifications built by hand.
add_executable(gate_verdict_test ${CMAKE_CURRENT_LIST_DIR}/tests/gate_verdict_test.cpp ${CMAKE_CURRENT_LIST_DIR}/tests/junit_test.cpp)
target_link_libraries(gate_verdict_test PRIVATE cullcheck_reports GTest::gtest_main cullcheck_warnings)
add_test(NAME gate_verdict_test COMMAND gate_verdict_test)

# The fuzzer's in-process run of built-in methods (the soak): counts and claims.
add_executable(fuzzing_test ${CMAKE_CURRENT_LIST_DIR}/tests/fuzzing_test.cpp)
target_link_libraries(fuzzing_test PRIVATE cullcheck_reports GTest::gtest_main cullcheck_warnings)
add_test(NAME fuzzing_test COMMAND fuzzing_test)

# Violations pass the oracle's double-precision witness re-check; report.json counts it.
add_executable(witness_recheck_report_test ${CMAKE_CURRENT_LIST_DIR}/tests/witness_recheck_report_test.cpp)
target_link_libraries(witness_recheck_report_test PRIVATE cullcheck_reports GTest::gtest_main cullcheck_warnings)
add_test(NAME witness_recheck_report_test COMMAND witness_recheck_report_test)

# The ε sweep's rows (report.json region_sweep[]) on a small seeded city.
add_executable(region_sweep_test ${CMAKE_CURRENT_LIST_DIR}/tests/region_sweep_test.cpp)
target_link_libraries(region_sweep_test PRIVATE cullcheck_reports cullcheck_generators GTest::gtest_main cullcheck_warnings)
add_test(NAME region_sweep_test COMMAND region_sweep_test)
add_executable(scaling_test ${CMAKE_CURRENT_LIST_DIR}/tests/scaling_test.cpp)
target_link_libraries(scaling_test PRIVATE cullcheck_reports cullcheck_generators GTest::gtest_main cullcheck_warnings)
add_test(NAME scaling_test COMMAND scaling_test)

# The report page: text helpers, SVG plots, the page from hand-made reports, the map's frame.
add_executable(report_page_test ${CMAKE_CURRENT_LIST_DIR}/html/tests/html_text_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/html/tests/svg_plot_test.cpp ${CMAKE_CURRENT_LIST_DIR}/html/tests/report_page_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/html/tests/frame_map_test.cpp)
target_link_libraries(report_page_test PRIVATE cullcheck_report_page cullcheck_reports GTest::gtest_main cullcheck_warnings)
add_test(NAME report_page_test COMMAND report_page_test)

# The report page in headless Chromium (a short main job; the screenshot is the run's artifact).
add_test(NAME report_page_browser_test COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/html/tests/browser_test.sh $<TARGET_FILE:cullcheck>
  ${PROJECT_BINARY_DIR}/artifacts)

# The knob sweep (report --knob-sweep): the flag, the methods each knob reaches, a sweep on a small city.
add_executable(knob_sweep_test ${CMAKE_CURRENT_LIST_DIR}/tests/knob_sweep_test.cpp)
target_link_libraries(knob_sweep_test PRIVATE cullcheck_reports cullcheck_generators GTest::gtest_main cullcheck_warnings)
add_test(NAME knob_sweep_test COMMAND knob_sweep_test)

# Claim searches on every core: the same ledger as one thread.
add_executable(claims_search_test ${CMAKE_CURRENT_LIST_DIR}/tests/claims_search_test.cpp)
target_link_libraries(claims_search_test PRIVATE cullcheck_reports GTest::gtest_main cullcheck_warnings)
add_test(NAME claims_search_test COMMAND claims_search_test)

# Shards of a run joined again (--shard K/N, cullcheck merge): four merged shards equal one run.
add_executable(shard_merge_test ${CMAKE_CURRENT_LIST_DIR}/tests/shard_merge_test.cpp)
target_link_libraries(shard_merge_test PRIVATE cullcheck_reports cullcheck_generators GTest::gtest_main cullcheck_warnings)
add_test(NAME shard_merge_test COMMAND shard_merge_test)
add_executable(report_same ${CMAKE_CURRENT_LIST_DIR}/tests/report_same.cpp)
target_link_libraries(report_same PRIVATE cullcheck_reports cullcheck_warnings)
add_test(NAME shard_cli_test COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/tests/shard_cli_test.sh $<TARGET_FILE:cullcheck>
  $<TARGET_FILE:report_same> ${PROJECT_BINARY_DIR}/examples/subjects)

# Issue 17's speed targets read off hand-made reports (report.json's "speed_targets").
add_executable(table_4_1_test ${CMAKE_CURRENT_LIST_DIR}/tests/table_4_1_test.cpp)
target_link_libraries(table_4_1_test PRIVATE cullcheck_reports GTest::gtest_main cullcheck_warnings)
add_test(NAME table_4_1_test COMMAND table_4_1_test)

add_executable(speed_targets_test ${CMAKE_CURRENT_LIST_DIR}/tests/speed_targets_test.cpp)
target_link_libraries(speed_targets_test PRIVATE cullcheck_reports GTest::gtest_main cullcheck_warnings)
add_test(NAME speed_targets_test COMMAND speed_targets_test)
