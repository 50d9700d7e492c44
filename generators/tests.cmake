# The generators' tests (properties/generators_test.cpp). Include this from
# properties/CMakeLists.txt, after cullcheck_property_main is defined:
#   include(${PROJECT_SOURCE_DIR}/generators/tests.cmake)
# It uses the shared property main (fixed RapidCheck seed and budget) when that target exists,
# GoogleTest's own main otherwise.
if(TARGET cullcheck_generators_rc AND TARGET rapidcheck AND TARGET GTest::gtest)
  add_executable(generators_test ${CMAKE_CURRENT_LIST_DIR}/../properties/generators_test.cpp)
  if(TARGET cullcheck_property_main)
    target_link_libraries(generators_test PRIVATE cullcheck_property_main)
  else()
    target_link_libraries(generators_test PRIVATE GTest::gtest_main)
  endif()
  target_link_libraries(generators_test PRIVATE cullcheck_generators cullcheck_generators_rc rapidcheck_gtest rapidcheck
                                                GTest::gtest cullcheck_warnings)
  if(COMMAND cullcheck_add_property_test)
    cullcheck_add_property_test(generators_test LABELS generators TIMEOUT 600)
  else()
    add_test(NAME generators_test COMMAND generators_test)
    set_tests_properties(generators_test PROPERTIES LABELS generators TIMEOUT 600)
  endif()
endif()

# Literal pins of the generators' output (generators/tests/pinned_streams_test.cpp): a changed
# random stream invalidates every stored replay, and fails here. Plain GoogleTest, no RapidCheck.
# The generated terrains' tests (tests/terrain_gen_test.cpp) are plain GoogleTest too, and ride along.
if(TARGET GTest::gtest)
  add_executable(generator_pins_test ${CMAKE_CURRENT_LIST_DIR}/tests/pinned_streams_test.cpp
                                    ${CMAKE_CURRENT_LIST_DIR}/tests/terrain_gen_test.cpp
                                    ${CMAKE_CURRENT_LIST_DIR}/tests/detailed_buildings_test.cpp)
  target_link_libraries(generator_pins_test PRIVATE cullcheck_generators GTest::gtest_main cullcheck_warnings)
  add_test(NAME generator_pins_test COMMAND generator_pins_test)
  set_tests_properties(generator_pins_test PROPERTIES LABELS generators)
endif()
