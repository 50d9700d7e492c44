# Unit tests of the subject protocol, the child process and the subject methods (GoogleTest).
# Included by properties/CMakeLists.txt, where enable_testing() is in effect. The subject tests
# run `sh -c` one-liners and a python3 script subject (scripted_subject.py, named by path; the
# path must not hold spaces, as the command line is split on them).
add_executable(subjects_test
  ${CMAKE_CURRENT_LIST_DIR}/child_process_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/protocol_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/recorded_pvs_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/subject_method_test.cpp)
target_link_libraries(subjects_test PRIVATE cullcheck_subjects cullcheck_core GTest::gtest_main cullcheck_warnings)
target_compile_definitions(subjects_test PRIVATE CULLCHECK_SCRIPTED_SUBJECT="${CMAKE_CURRENT_LIST_DIR}/scripted_subject.py")
add_test(NAME subjects_test COMMAND subjects_test)
set_tests_properties(subjects_test PROPERTIES TIMEOUT 120)
