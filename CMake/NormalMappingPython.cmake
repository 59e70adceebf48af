# SPDX-License-Identifier: BSD-3-Clause
# Python wrapping of VTK::NormalMapping in the standalone build, with VTK's own wrapping tools.
# (Inside a VTK source tree VTK wraps the module itself, into its vtkmodules package.)
#
# Included after find_package(VTK): decides whether to wrap and says why in one status line,
#   NORMALMAPPING_PYTHON_ENABLED   ON or OFF
#   NORMALMAPPING_PYTHON_EXECUTABLE the interpreter the wrapped package is for (tests run it)
#   NORMALMAPPING_PYTHON_DESTINATION where the package goes, relative to the build tree and to the
#                                  install prefix
# and defines normalmapping_wrap_python(<modules>), called after vtk_module_build.
#
# The package is `vtknormalmapping`: all lower case like VTK's own `vtkmodules` (PEP 8 package
# naming), and not `vtkmodules.vtkNormalMapping`, because `vtkmodules` is VTK's installed
# package and cannot be extended from another folder.
option(NORMALMAPPING_WRAP_PYTHON
  "Wrap the module for Python (on when this VTK is wrapped and a Python with development files that imports VTK is found)"
  ON)

set(NORMALMAPPING_PYTHON_ENABLED OFF)
set(_nm_python_reason "")
if(NOT NORMALMAPPING_WRAP_PYTHON)
  set(_nm_python_reason "NORMALMAPPING_WRAP_PYTHON is OFF")
elseif(NOT VTK_WRAP_PYTHON)
  set(_nm_python_reason "this VTK (${VTK_DIR}) has no Python wrapping")
elseif(NOT BUILD_SHARED_LIBS)
  set(_nm_python_reason "BUILD_SHARED_LIBS is OFF (VTK's Python modules need shared libraries)")
else()
  # The interpreter must be the one VTK's Python modules were built for. Unless
  # Python3_EXECUTABLE is given, take the python3 of VTK's own prefix (Debian: /usr/bin/python3)
  # rather than the first python3 on PATH, which may be another installation (pyenv, a venv)
  # without VTK.
  if(NOT Python3_EXECUTABLE)
    find_program(_nm_vtk_python
      NAMES "python${VTK_PYTHON_VERSION}" python3
      PATHS "${VTK_PREFIX_PATH}/bin"
      NO_DEFAULT_PATH)
    if(_nm_vtk_python)
      set(Python3_EXECUTABLE "${_nm_vtk_python}" CACHE FILEPATH
        "The Python interpreter to wrap for (default: the one in VTK's prefix)")
    endif()
  endif()
  # VTK's Python component runs find_package(Python3 <VTK's version> COMPONENTS Interpreter
  # Development.Module) and gives VTK::WrappingPythonCore and VTK::Python.
  find_package(VTK QUIET OPTIONAL_COMPONENTS Python WrappingPythonCore)
  if(NOT Python3_Interpreter_FOUND)
    set(_nm_python_reason "no Python interpreter found (set Python3_EXECUTABLE)")
  elseif(NOT Python3_Development.Module_FOUND)
    set(_nm_python_reason
      "the Python development files for ${Python3_EXECUTABLE} are missing (Debian: python3-dev)")
  elseif(NOT TARGET VTK::WrapPython OR NOT TARGET VTK::WrapPythonInit OR
      NOT TARGET VTK::WrappingPythonCore)
    set(_nm_python_reason "VTK's Python wrapping tools are missing")
  else()
    # The package would be useless if this interpreter cannot import this VTK's modules.
    execute_process(
      COMMAND "${Python3_EXECUTABLE}" -c
        "import vtkmodules.vtkRenderingOpenGL2, vtkmodules.vtkCommonCore as c; print(c.vtkVersion.GetVTKVersion())"
      RESULT_VARIABLE _nm_python_rc
      OUTPUT_VARIABLE _nm_python_vtk
      ERROR_VARIABLE _nm_python_err
      OUTPUT_STRIP_TRAILING_WHITESPACE)
    if(NOT _nm_python_rc EQUAL 0)
      set(_nm_python_reason
        "${Python3_EXECUTABLE} cannot import VTK's Python modules (Debian: python3-vtk9), or set Python3_EXECUTABLE to the Python VTK was built for")
    elseif(NOT _nm_python_vtk VERSION_EQUAL VTK_VERSION)
      set(_nm_python_reason
        "${Python3_EXECUTABLE} imports VTK ${_nm_python_vtk}, not this VTK ${VTK_VERSION}")
    else()
      set(NORMALMAPPING_PYTHON_ENABLED ON)
    endif()
  endif()
endif()

if(NORMALMAPPING_PYTHON_ENABLED)
  set(NORMALMAPPING_PYTHON_EXECUTABLE "${Python3_EXECUTABLE}")
  vtk_module_python_default_destination(_nm_python_default_destination)
  set(NORMALMAPPING_PYTHON_DESTINATION "${_nm_python_default_destination}" CACHE STRING
    "Where the vtknormalmapping package goes, relative to the build tree and the install prefix")
  message(STATUS "NormalMapping: Python wrapping ON: package vtknormalmapping for "
    "${Python3_EXECUTABLE} (Python ${Python3_VERSION}, VTK ${_nm_python_vtk}), in "
    "<build or prefix>/${NORMALMAPPING_PYTHON_DESTINATION}")
else()
  message(STATUS "NormalMapping: Python wrapping OFF: ${_nm_python_reason}")
endif()

# Wraps `modules` into the package vtknormalmapping: the extension vtkNormalMapping (one per
# module, as VTK names them) and an __init__.py that imports its classes.
function(normalmapping_wrap_python modules)
  vtk_module_wrap_python(
    MODULES ${modules}
    PYTHON_PACKAGE vtknormalmapping
    MODULE_DESTINATION "${NORMALMAPPING_PYTHON_DESTINATION}"
    # The extension finds libvtkNormalMapping through an $ORIGIN-relative RPATH when installed.
    LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
    # The file that tells other projects' wrapping which package holds VTK::NormalMapping.
    CMAKE_DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/NormalMapping"
    # The interpreter's ABI tag in the file name: another Python version finds no module instead
    # of loading an incompatible one.
    SOABI "${Python3_SOABI}"
    BUILD_STATIC OFF
    WRAPPED_MODULES _nm_wrapped)
  if(NOT _nm_wrapped)
    message(FATAL_ERROR "NormalMapping: no module was wrapped for Python")
  endif()
  set(_nm_package_dir "${CMAKE_BINARY_DIR}/${NORMALMAPPING_PYTHON_DESTINATION}/vtknormalmapping")
  configure_file("${PROJECT_SOURCE_DIR}/Wrapping/Python/__init__.py"
    "${_nm_package_dir}/__init__.py" COPYONLY)
  install(FILES "${_nm_package_dir}/__init__.py"
    DESTINATION "${NORMALMAPPING_PYTHON_DESTINATION}/vtknormalmapping")
endfunction()
