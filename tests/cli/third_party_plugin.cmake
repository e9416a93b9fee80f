# Installs plumage into a scratch prefix, builds examples/third_party_plugin against it with
# find_package(plumage), and loads the result with the installed executable.
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/third_party_plugin -B ${WORK_DIR}/build
    -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${CMAKE_COMMAND} -E env PLUMAGE_PLUGIN_PATH=${WORK_DIR}/build ${WORK_DIR}/prefix/bin/plumage plugins)
if(NOT last_output MATCHES "local_reflection +constant_reflectance")
  message(FATAL_ERROR "the third-party plug-in is not listed:\n${last_output}")
endif()
run(${CMAKE_COMMAND} -E env PLUMAGE_PLUGIN_PATH=${WORK_DIR}/build ${WORK_DIR}/prefix/bin/plumage
    multilayer --model constant_reflectance --stack "air | keratin" --lambda-nm 500 --theta-deg 0)
# Default reflectance 0.04 -> amplitude 0.2, R = 0.04.
if(NOT last_output MATCHES "500,0,0.2,0,0.2,0,0.04")
  message(FATAL_ERROR "unexpected output of the third-party plug-in:\n${last_output}")
endif()
message(STATUS "third-party plug-in built out of tree and loaded")
