# Tests of the report libraries written next to them (GoogleTest). Included by
# properties/CMakeLists.txt, where enable_testing() is in effect.
add_executable(pictures_test ${CMAKE_CURRENT_LIST_DIR}/tests/pictures_test.cpp)
target_link_libraries(pictures_test PRIVATE cullcheck_pictures GTest::gtest_main cullcheck_warnings)
add_test(NAME pictures_test COMMAND pictures_test)
