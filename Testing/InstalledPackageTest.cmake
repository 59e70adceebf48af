# SPDX-License-Identifier: BSD-3-Clause
# Installs the module to a prefix, builds Examples/ as a separate project against it with
# find_package(NormalMapping), and runs the example and the normalmap tool: the packaging,
# tested on every change.
# With PYTHON (the interpreter) and PYTHON_DESTINATION (the package's folder under the prefix),
# it also runs the Python filter test against the installed package: with LD_LIBRARY_PATH unset,
# and it checks that both the package and the module library it loads come from the prefix.
# Inputs: BUILD_DIR, SOURCE_DIR, WORK_DIR, VTK_DIR (the VTK the module was built against: with
# only the prefix, find_package could pick another VTK, and two VTKs in one process crash);
# PYTHON, PYTHON_DESTINATION optional.
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
  -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix "-DVTK_DIR=${VTK_DIR}" -DCMAKE_BUILD_TYPE=Release)
run("${CMAKE_COMMAND}" --build "${WORK_DIR}/examples")
run("${WORK_DIR}/examples/TangentFramesDemo" --triangles 20000)
run("${WORK_DIR}/examples/normalmap/normalmap" tangents
  "${SOURCE_DIR}/Examples/normalmap/Testing/Data/quad.gltf" -o "${WORK_DIR}/quad.glb")
run("${WORK_DIR}/examples/normalmap/normalmap" render --help)
if(PYTHON)
  run("${CMAKE_COMMAND}" -E env --unset=LD_LIBRARY_PATH
    "PYTHONPATH=${WORK_DIR}/prefix/${PYTHON_DESTINATION}"
    "NORMALMAPPING_EXPECT_PREFIX=${WORK_DIR}/prefix" PYTHONDONTWRITEBYTECODE=1
    "${PYTHON}" "${SOURCE_DIR}/Testing/Python/TestTangentFramesPython.py")
endif()
