# Deployment checks (deploy/, examples/), included from tests/CMakeLists.txt. No Docker engine or
# cluster is needed: the manifests are checked statically, and the image's install step and
# runtime layout are exercised by installing this build into a staging prefix.

# deploy/Dockerfile, compose.yaml and k8s/*.yaml: required fields, consistency, and --self-test
# (each check must catch a broken copy of the files).
add_test(NAME deploy_manifests
         COMMAND /usr/bin/python3 ${CMAKE_SOURCE_DIR}/deploy/check_manifests.py --self-test)

# cmake --install into a staging prefix (as the Dockerfile does), the runtime libraries, then the
# installed server: probes, projections, examples/project_csv.sh, logs, metrics, SIGTERM -> exit 0.
if(TARGET footpoint-server)
  add_test(NAME deploy_layout
           COMMAND bash ${CMAKE_SOURCE_DIR}/deploy/check_layout.sh ${CMAKE_BINARY_DIR})
  set_tests_properties(deploy_layout PROPERTIES TIMEOUT 120)
endif()

# The installed binary exposed as docs/security.md describes, driven by curl (HTTPS with a
# certificate made by openssl at test time, API keys, rate limit, delete audit, SIGHUP reload).
if(TARGET footpoint-server)
  add_test(NAME server_security_e2e
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/e2e/server_security_e2e.sh $<TARGET_FILE:footpoint-server>)
  set_tests_properties(server_security_e2e PROPERTIES TIMEOUT 300)
endif()

# The shell scripts users and CI run, when shellcheck is installed (install-deps.sh --test).
find_program(FOOTPOINT_SHELLCHECK shellcheck)
if(FOOTPOINT_SHELLCHECK)
  file(GLOB FOOTPOINT_SCRIPTS ${CMAKE_SOURCE_DIR}/scripts/*.sh)
  add_test(NAME deploy_shellcheck
           COMMAND ${FOOTPOINT_SHELLCHECK} ${CMAKE_SOURCE_DIR}/deploy/check_layout.sh
                   ${CMAKE_SOURCE_DIR}/examples/project_csv.sh ${FOOTPOINT_SCRIPTS} ${CMAKE_SOURCE_DIR}/.ci/run
                   ${CMAKE_SOURCE_DIR}/tests/e2e/check_installed_package.sh ${CMAKE_SOURCE_DIR}/tests/e2e/openapi_lint.sh
                   ${CMAKE_SOURCE_DIR}/tests/e2e/server_security_e2e.sh)
endif()

# openapi.yaml through Redocly's linter with its recommended rules (tests/e2e/openapi_lint.sh installs
# the version tests/tools/redocly/package-lock.json pins; skipped without npm).
add_test(NAME openapi_lint COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/e2e/openapi_lint.sh ${CMAKE_SOURCE_DIR})
set_tests_properties(openapi_lint PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300)
