# Unit tests of the scene model, cameras and their JSON and matrices (GoogleTest). Included by
# properties/CMakeLists.txt, where enable_testing() is in effect.
add_executable(core_test
  ${CMAKE_CURRENT_LIST_DIR}/camera_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/camera_matrices_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/coordinates_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/scene_mesh_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/progress_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/background_task_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/parallel_indices_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/terrain_test.cpp)
target_link_libraries(core_test PRIVATE cullcheck_core GTest::gtest_main cullcheck_warnings)
add_test(NAME core_test COMMAND core_test)
