# The mesh formats' tests (GoogleTest). Included by properties/CMakeLists.txt, where
# enable_testing() is in effect. They build glTF files by hand through tinygltf's model API, so
# they link TinyGLTF themselves.
if(TARGET GTest::gtest)
  add_executable(formats_test
    ${CMAKE_CURRENT_LIST_DIR}/geojson_import_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/cityjson_import_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/dem_import_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/gltf_import_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/index_limits_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/obj_import_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/polygon_triangulation_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/round_trip_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/vertical_prism_test.cpp)
  target_link_libraries(formats_test PRIVATE cullcheck_formats cullcheck_generators TinyGLTF::TinyGLTF GTest::gtest_main
                                             cullcheck_warnings)
  # The real data beside the checkout (../shared/data, as CI lays it out).
  target_compile_definitions(formats_test PRIVATE CULLCHECK_SHARED_DATA="${PROJECT_SOURCE_DIR}/../shared/data")
  add_test(NAME formats_test COMMAND formats_test)
  set_tests_properties(formats_test PROPERTIES LABELS formats TIMEOUT 600)
endif()
