# Installs the module to a prefix, builds Examples/ as a separate project against it with
# find_package(NormalMapping), and runs the example and the normalmap tool: the packaging,
# tested on every change.
# Inputs: BUILD_DIR, SOURCE_DIR, WORK_DIR.
file(REMOVE_RECURSE "${WORK_DIR}")
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}")
  endif()
  message("${out}")
endfunction()
run("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix")
run("${CMAKE_COMMAND}" -S "${SOURCE_DIR}/Examples" -B "${WORK_DIR}/examples"
  -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release)
run("${CMAKE_COMMAND}" --build "${WORK_DIR}/examples")
run("${WORK_DIR}/examples/TangentFramesDemo" --triangles 20000)
run("${WORK_DIR}/examples/normalmap/normalmap" tangents
  "${SOURCE_DIR}/Examples/normalmap/Testing/Data/quad.gltf" -o "${WORK_DIR}/quad.glb")
run("${WORK_DIR}/examples/normalmap/normalmap" render --help)
