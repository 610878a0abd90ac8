# The shared geometry registry against a real redis-server and real footpoint-server processes,
# included from tests/CMakeLists.txt. Skipped (exit code 77) when redis-server is not installed.
if(TARGET footpoint-server)
  file(GLOB FOOTPOINT_REGISTRY_TESTS CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/registry/*.cpp)
  add_executable(test_registry ${FOOTPOINT_REGISTRY_TESTS})
  target_link_libraries(test_registry PRIVATE footpoint_server_lib doctest::doctest nlohmann_json::nlohmann_json)
  target_include_directories(test_registry PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(test_registry PRIVATE FOOTPOINT_SERVER_BINARY="$<TARGET_FILE:footpoint-server>")
  add_dependencies(test_registry footpoint-server)
  add_test(NAME test_registry COMMAND test_registry)
  set_tests_properties(test_registry PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300)
endif()
