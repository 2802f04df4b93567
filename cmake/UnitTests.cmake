# pvtap_unit_tests(FOLDER [PREFIX p] [TEST_PREFIX t] LIBRARIES lib...): a GoogleTest program
# for every *_test.cpp of FOLDER (relative to the calling CMakeLists.txt), named p<file name>,
# linked with LIBRARIES and tests/support; its tests are discovered into CTest as
# t<Suite>.<Test> with the label unit. One program per source file keeps failures easy to
# locate and runs in parallel.
find_package(GTest REQUIRED)
include(GoogleTest)

# Test code is optimised for the time it takes to build, not to run: its bodies run in
# milliseconds, and optimising them at -O3 took about a third of a Release build's CPU. The
# products under test keep their own flags; -Og rather than -O0 keeps _FORTIFY_SOURCE (the
# package's hardening flags) working.
set(PVTAP_TEST_CODE_OPTIONS $<$<CONFIG:Release,RelWithDebInfo,MinSizeRel>:-Og>)

# pvtap_unit_programs: every program the unit and corpus tests run (the unit test programs, and
# from fuzz/ the corpus replays). The sanitizer build of scripts/test builds it with pvtap and
# the plugin, and not the simulator, which only the integration tests need.
if(NOT TARGET pvtap_unit_programs)
  add_custom_target(pvtap_unit_programs)
endif()

function(pvtap_unit_tests folder)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "PREFIX;TEST_PREFIX" "LIBRARIES")
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${folder}/*_test.cpp)
  foreach(source IN LISTS sources)
    get_filename_component(name ${source} NAME_WE)
    set(program ${arg_PREFIX}${name})
    add_executable(${program} ${source})
    target_compile_options(${program} PRIVATE ${PVTAP_WARNINGS} ${PVTAP_TEST_CODE_OPTIONS})
    target_include_directories(${program} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
    target_link_libraries(${program} PRIVATE ${arg_LIBRARIES} GTest::gtest_main)
    add_dependencies(pvtap_unit_programs ${program})
    if(arg_TEST_PREFIX)
      gtest_discover_tests(${program} DISCOVERY_TIMEOUT 60 TEST_PREFIX ${arg_TEST_PREFIX}
                           PROPERTIES LABELS unit)
    else()
      gtest_discover_tests(${program} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS unit)
    endif()
  endforeach()
endfunction()
