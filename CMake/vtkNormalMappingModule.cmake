# SPDX-License-Identifier: BSD-3-Clause
# The body of the VTK::NormalMapping module: its classes and private kernels.
# NORMALMAPPING_SOURCE_DIR is the project root.
find_package(glm REQUIRED)

set(_nm_classes
  Filters/vtkPolyDataTangentFrames
  Rendering/vtkNormalMapCompositePolyDataMapper
  Rendering/vtkNormalMapObjectFactory
  Rendering/vtkNormalMapPolyDataMapper)
# Installed, but not wrapped for Python: VTK 9.1's wrappers wrap only classes, and only enums and
# constants of namespaces, so these free functions and plain structs would give nothing usable.
set(_nm_nowrap_headers
  Filters/vtkMikkTSpaceKernel.h
  Filters/vtkNormalMappingMeshes.h
  Filters/vtkTangentFrameChecks.h)
set(_nm_sources
  Filters/vtkMikkTSpaceKernel.cxx
  Filters/vtkNormalMappingMeshes.cxx
  Filters/vtkNormalMappingPrivate.cxx
  Filters/vtkPolyDataTangentFramesMikkTSpace.cxx
  Filters/vtkPolyDataTangentFramesSupplied.cxx
  Filters/vtkPolyDataTangentFramesWeighted.cxx
  Filters/vtkTangentFrameChecks.cxx
  Rendering/vtkNormalMapShading.cxx)
# Not installed. vtkTangentFrameKernels.h (the math, over GLM vectors) is reachable from the
# build tree, so that the tests call its functions directly.
set(_nm_private_headers
  Filters/vtkNormalMappingMultiversioning.h
  Filters/vtkNormalMappingPrivate.h
  Filters/vtkTangentFrameKernels.h
  Rendering/vtkNormalMapShading.h)

# The filter's sources, compiled without fused multiply-adds (below).
set(_nm_filter_sources ${_nm_sources})
list(FILTER _nm_filter_sources INCLUDE REGEX "^Filters/")
list(APPEND _nm_filter_sources Filters/vtkPolyDataTangentFrames.cxx)
list(TRANSFORM _nm_filter_sources PREPEND "${NORMALMAPPING_SOURCE_DIR}/")

list(TRANSFORM _nm_classes PREPEND "${NORMALMAPPING_SOURCE_DIR}/")
list(TRANSFORM _nm_nowrap_headers PREPEND "${NORMALMAPPING_SOURCE_DIR}/")
list(TRANSFORM _nm_sources PREPEND "${NORMALMAPPING_SOURCE_DIR}/")
list(TRANSFORM _nm_private_headers PREPEND "${NORMALMAPPING_SOURCE_DIR}/")

# The mapper's GLSL lives in Rendering/glsl and is embedded as C strings at build time.
if(NOT COMMAND vtk_encode_string) # inside a VTK source tree it is loaded already
  include("${VTK_DIR}/vtkEncodeString.cmake")
endif()
foreach(_nm_shader IN ITEMS vtkNormalMapVS vtkNormalMapGS vtkNormalMapFS)
  vtk_encode_string(
    INPUT "${NORMALMAPPING_SOURCE_DIR}/Rendering/glsl/${_nm_shader}.glsl"
    EXPORT_SYMBOL "VTKNORMALMAPPING_NO_EXPORT"
    EXPORT_HEADER "vtkNormalMappingModule.h"
    HEADER_OUTPUT _nm_shader_header
    SOURCE_OUTPUT _nm_shader_source)
  list(APPEND _nm_sources "${_nm_shader_source}")
  list(APPEND _nm_private_headers "${_nm_shader_header}")
endforeach()

# The MikkTSpace kernel reproduces the reference's float rounding, and the filter gives the same
# bits on every CPU (the weighted methods' frame loop is compiled for several instruction sets,
# and the supplied-tangent checks must find the handedness the methods give): no fused
# multiply-add (GCC contracts by default and ignores the STDC FP_CONTRACT pragma the MikkTSpace
# source carries for others). The filter reads neither errno nor floating-point exception flags,
# so sqrt and divisions may be vectorised (with the default -fmath-errno / -ftrapping-math GCC
# keeps them scalar); neither option changes a result.
if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  set_property(SOURCE ${_nm_filter_sources}
    APPEND PROPERTY COMPILE_OPTIONS -ffp-contract=off -fno-math-errno -fno-trapping-math)
endif()

# The filter's vector loops are compiled also for AVX2 and AVX-512 where the compiler can
# (VTK_NORMALMAPPING_TARGET_CLONES in Filters/vtkNormalMappingMultiversioning.h). OFF compiles
# them once, for the default target, as other compilers and CPUs do; the benchmark measures such
# a build.
option(NORMALMAPPING_MULTIVERSIONING
  "Compile the filter's vector loops also for AVX2 and AVX-512 (GCC, Clang 14+; x86-64 Linux)" ON)
mark_as_advanced(NORMALMAPPING_MULTIVERSIONING)

# The headers live in Filters/ and Rendering/ and install side by side into one include folder,
# as consumers include them (ctest InstalledPackageExample). VTK 9.4 and later warn about every
# header outside the module's own folder, suggesting a layout that would install them into
# subfolders; those warnings (errors under -Werror=dev) are silenced for this one call.
# (-Wno-dev, -Wdev and -Werror=dev set cache entries, which the unsets below uncover again.)
set(CMAKE_SUPPRESS_DEVELOPER_WARNINGS ON)
set(CMAKE_SUPPRESS_DEVELOPER_ERRORS ON)
vtk_module_add_module(VTK::NormalMapping
  CLASSES ${_nm_classes}
  NOWRAP_HEADERS ${_nm_nowrap_headers}
  SOURCES ${_nm_sources}
  PRIVATE_HEADERS ${_nm_private_headers})
unset(CMAKE_SUPPRESS_DEVELOPER_WARNINGS)
unset(CMAKE_SUPPRESS_DEVELOPER_ERRORS)
vtk_module_include(VTK::NormalMapping
  PUBLIC
    "$<BUILD_INTERFACE:${NORMALMAPPING_SOURCE_DIR}/Filters>"
    "$<BUILD_INTERFACE:${NORMALMAPPING_SOURCE_DIR}/Rendering>")
# GLM is a private detail of the filters; tests that include the kernels header link it themselves.
vtk_module_link(VTK::NormalMapping PRIVATE glm::glm)
vtk_module_compile_features(VTK::NormalMapping PUBLIC cxx_std_17)
if(NOT NORMALMAPPING_MULTIVERSIONING)
  vtk_module_definitions(VTK::NormalMapping PRIVATE VTK_NORMALMAPPING_NO_MULTIVERSIONING)
endif()
