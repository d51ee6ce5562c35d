# Run after a test executable is built (test/CMakeLists.txt): writes CTEST_FILE, which gives
# each of the executable's tests its CTest labels. Catch2's discovery (Catch.cmake) adds the
# tests; this file, included after it, only labels them:
#   - the folder of the test's source file under test/ (image, io, simplify, volume, delaunay,
#     cli, common): the capability it covers;
#   - cli for a test_cli_*.cpp in any folder (it runs the ddtup executable);
#   - each of the test's Catch2 tags that is one of LABEL_TAGS (vulkan, heavy, threads…).
# Fails when a test tagged [threads] is in an executable that ThreadSanitizer's tier does not
# build (THREADS_ALLOWED off), so that no such test is left out unseen.
# -D TEST_EXECUTABLE=… -D TEST_ROOT=<test/ folder> -D LABEL_TAGS=a,b -D THREADS_ALLOWED=ON|OFF
# -D CTEST_FILE=…
cmake_minimum_required(VERSION 3.25)
execute_process(COMMAND "${TEST_EXECUTABLE}" --list-labels
                OUTPUT_VARIABLE listing RESULT_VARIABLE result ERROR_VARIABLE error)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${TEST_EXECUTABLE} --list-labels failed (${result}): ${error}")
endif()
string(REPLACE "," ";" label_tags "${LABEL_TAGS}")
string(REPLACE "\n" ";" lines "${listing}")
set(script "")
foreach(line IN LISTS lines)
  if(line STREQUAL "")
    continue()
  endif()
  string(REPLACE "\t" ";" fields "${line}")
  list(GET fields 0 name)
  list(GET fields 1 file)
  list(LENGTH fields count)
  set(tags "")
  if(count GREATER 2)
    list(GET fields 2 tags)
    string(REPLACE "," ";" tags "${tags}")
  endif()
  file(RELATIVE_PATH relative "${TEST_ROOT}" "${file}")
  string(REGEX MATCH "^[^/]+/" folder "${relative}")
  if(NOT folder)
    message(FATAL_ERROR "${name}: its source ${file} is not in a folder of ${TEST_ROOT}")
  endif()
  string(REGEX REPLACE "/$" "" labels "${folder}")
  get_filename_component(base "${file}" NAME)
  if(base MATCHES "^test_cli_" AND NOT labels STREQUAL "cli")
    list(APPEND labels cli)
  endif()
  if("threads" IN_LIST tags AND NOT THREADS_ALLOWED)
    message(FATAL_ERROR "${name} is tagged [threads], but ${relative}'s folder is not in test/CMakeLists.txt's "
                        "threads_folders, which ThreadSanitizer's tier builds")
  endif()
  foreach(tag IN LISTS tags)
    if(tag IN_LIST label_tags)
      list(APPEND labels ${tag})
    endif()
  endforeach()
  string(APPEND script "set_tests_properties([==[${name}]==] PROPERTIES LABELS \"${labels}\")\n")
endforeach()
file(WRITE "${CTEST_FILE}" "${script}")
