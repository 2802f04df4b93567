# pvtap_unit_tests(FOLDER [PREFIX p] [TEST_PREFIX t] LIBRARIES lib...): a GoogleTest program
# for every *_test.cpp of FOLDER (relative to the calling CMakeLists.txt), named p<file name>,
# linked with LIBRARIES and tests/support; its tests are discovered into CTest as
# t<Suite>.<Test> with the label unit. One program per source file keeps failures easy to
# locate and runs in parallel.
find_package(GTest REQUIRED)
include(GoogleTest)

function(pvtap_unit_tests folder)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "PREFIX;TEST_PREFIX" "LIBRARIES")
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${folder}/*_test.cpp)
  foreach(source IN LISTS sources)
    get_filename_component(name ${source} NAME_WE)
    set(program ${arg_PREFIX}${name})
    add_executable(${program} ${source})
    target_compile_options(${program} PRIVATE ${PVTAP_WARNINGS})
    target_include_directories(${program} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
    target_link_libraries(${program} PRIVATE ${arg_LIBRARIES} GTest::gtest_main)
    if(arg_TEST_PREFIX)
      gtest_discover_tests(${program} DISCOVERY_TIMEOUT 60 TEST_PREFIX ${arg_TEST_PREFIX}
                           PROPERTIES LABELS unit)
    else()
      gtest_discover_tests(${program} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS unit)
    endif()
  endforeach()
endfunction()
