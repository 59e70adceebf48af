# SPDX-License-Identifier: BSD-3-Clause
# Builds the module the way a VTK source tree builds a remote module: a top-level project named
# VTK scans <tree>/Remote/NormalMapping/vtk.module and lets vtk_module_build add that directory,
# so the root CMakeLists.txt runs as the module's body. (The real VTK tree is too large to build
# here; this runs the same vtk_module_scan / vtk_module_build path against the installed VTK.)
# Inputs: SOURCE_DIR (this project), WORK_DIR, VTK_DIR (the VTK the project was configured with).
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/src/Remote")
file(COPY "${SOURCE_DIR}/" DESTINATION "${WORK_DIR}/src/Remote/NormalMapping"
  PATTERN ".git" EXCLUDE PATTERN "build*" EXCLUDE)
file(WRITE "${WORK_DIR}/src/CMakeLists.txt" [=[
cmake_minimum_required(VERSION 3.12)
project(VTK C CXX)
set(CMAKE_CXX_STANDARD 17)
include(GNUInstallDirs)
find_package(VTK REQUIRED COMPONENTS CommonCore CommonDataModel CommonExecutionModel CommonMath
  RenderingCore RenderingOpenGL2)
vtk_module_scan(MODULE_FILES "${CMAKE_SOURCE_DIR}/Remote/NormalMapping/vtk.module"
  REQUEST_MODULES VTK::NormalMapping PROVIDES_MODULES modules ENABLE_TESTS OFF)
vtk_module_build(MODULES ${modules} INSTALL_EXPORT RemoteTest ENABLE_WRAPPING OFF
  CMAKE_DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/remote-test")
]=])
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}")
  endif()
endfunction()
run("${CMAKE_COMMAND}" -S "${WORK_DIR}/src" -B "${WORK_DIR}/build" -DCMAKE_BUILD_TYPE=Release
  "-DVTK_DIR=${VTK_DIR}")
run("${CMAKE_COMMAND}" --build "${WORK_DIR}/build")
message("remote-module layout: VTK::NormalMapping built as a module of a project named VTK")
