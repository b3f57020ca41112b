# p4_library(NAME name SOURCES ... DEPS ...): one static library per folder of src/p4.
function(p4_library)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(${ARG_NAME} STATIC ${ARG_SOURCES})
  target_include_directories(${ARG_NAME} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(${ARG_NAME} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  target_compile_options(${ARG_NAME} PRIVATE -Wall -Wextra -Wpedantic)
endfunction()

# p4_test(NAME name SOURCES ... DEPS ... [WHOLE]): one GoogleTest binary, run from the project
# root. Each TEST becomes a CTest test, unless WHOLE: then the binary is one CTest test (for
# end-to-end suites whose fixture does expensive work once).
function(p4_test)
  cmake_parse_arguments(ARG "WHOLE" "NAME" "SOURCES;DEPS" ${ARGN})
  if(NOT P4_BUILD_TESTS)
    return()
  endif()
  add_executable(${ARG_NAME} ${ARG_SOURCES})
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${ARG_NAME} PRIVATE
    P4_SHARED_DATA="${PROJECT_SOURCE_DIR}/../shared/data"
    P4_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  if(ARG_WHOLE)
    add_test(NAME ${ARG_NAME} COMMAND ${ARG_NAME} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  else()
    gtest_discover_tests(${ARG_NAME} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
      DISCOVERY_TIMEOUT 60)
  endif()
endfunction()
